// The OpenCL layer rcsplat's passes share: one device, its context and queue, and a per-device program cache.
#pragma once
#include <CL/opencl.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cl/device_info.h"

namespace rcsplat {

// Compile-time switches for a program: "-D NAME=VALUE" pairs, chosen from the scene by the caller.
using KernelDefines = std::map<std::string, std::string>;

class GpuContext {
 public:
  explicit GpuContext(const DeviceInfo& device);

  const DeviceInfo& device_info() const { return info_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // The program built from kernels/<file> (its includes resolved) with the given switches; built once per device and
  // set of switches, and kept on disk between runs (see program_cache.cpp). Throws rcsplat::Error with the build log.
  cl::Program& program(const std::string& file, const KernelDefines& defines = {});

  // Seconds spent building (or loading cached) programs so far, for the summary.
  double program_seconds() const { return program_seconds_; }

  template <typename T>
  cl::Buffer upload(const std::vector<T>& data, cl_mem_flags flags = CL_MEM_READ_ONLY) {
    // Zero-sized buffers are invalid in OpenCL: keep one element so a kernel argument is always valid.
    size_t bytes = std::max<size_t>(data.size(), 1) * sizeof(T);
    cl::Buffer buffer(context_, flags, bytes);
    if (!data.empty()) queue_.enqueueWriteBuffer(buffer, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    return buffer;
  }

  template <typename T>
  std::vector<T> download(const cl::Buffer& buffer, size_t count) {
    std::vector<T> data(count);
    if (count) queue_.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(T), data.data());
    return data;
  }

 private:
  DeviceInfo info_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::map<std::string, std::unique_ptr<cl::Program>> programs_;
  double program_seconds_ = 0.0;
};

// Where kernel sources come from: the embedded copies, or a folder when RCSPLAT_KERNEL_DIR is set (developer mode:
// edit a kernel and rerun without rebuilding).
std::string kernel_source_dir();

// The text of kernels/<file> with every #include "x" replaced by x's text (once per file), framed by #line directives
// so that compiler messages name the original file and line.
std::string resolve_kernel_source(const std::string& file);

}  // namespace rcsplat
