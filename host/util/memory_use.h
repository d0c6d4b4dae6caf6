// Memory a run needed: device buffers by use (counted by GpuContext) and the process's peak resident set.
#pragma once
#include <sys/resource.h>

#include <cstddef>
#include <map>
#include <string>

namespace rcsplat {

// Device memory in use through GpuContext::buffer, by the name each buffer was made with: now and at the peak.
struct DeviceMemoryUse {
  size_t live_bytes = 0, peak_bytes = 0;
  std::map<std::string, size_t> live_by_use, at_peak_by_use;
};

// The most resident memory this process has held so far (Linux reports ru_maxrss in KiB).
inline size_t peak_host_bytes() {
  rusage usage{};
  return getrusage(RUSAGE_SELF, &usage) == 0 ? size_t(usage.ru_maxrss) * 1024 : 0;
}

}  // namespace rcsplat
