// The OpenCL layer rcsplat's passes share: one device, its context and queue, and a per-device program cache.
#pragma once
#include <CL/opencl.hpp>

#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "cl/device_info.h"
#include "cl/named_kernel.h"
#include "util/test_probe.h"
#include "util/memory_use.h"

namespace rcsplat {

// Compile-time switches for a program: "-D NAME=VALUE" pairs, chosen from the scene by the caller.
using KernelDefines = std::map<std::string, std::string>;

// Work-group sizes by kind of kernel, chosen for the device at run time.
enum class RecordTrace { fused, split, wavefront };
const char* record_trace_name(RecordTrace shape);

struct GroupSizes {
  size_t traversal = 64;  // a ray (or pixel) per work-item, tracing: PoCL runs 15% slower when it picks the size
  size_t per_record = 8;  // a record per work-item, reducing its hundreds of samples
  // Samples of one record a work-item of the record trace takes: a GPU wants a work-item per ray; PoCL's CPU device
  // ran Sponza's record pass 14% slower that way than with 32 (the record's site and cones loaded once for all).
  size_t record_samples_per_item = 32;
  // The record trace's shape (kernels/records.cl), the same samples whichever: one kernel tracing and shading each
  // ray (fused); one tracing each ray to its closest hit and one shading the hits (split: on an H100 the one kernel
  // used 225 registers, the two 128 and 229, and the record pass took 0.58x the time); or split with the path after
  // the first hit queued, a kernel a bounce (wavefront: no kernel holds a path's loop). PoCL is fastest fused.
  RecordTrace record_trace = RecordTrace::fused;
  // Samples a launch of the record trace takes at most (20 bytes each kept until reduced, 36 with a split trace's
  // hits, 112 with the wavefront's queued paths): 2^21 fills any GPU many times over and keeps 40 MiB (72, 224 MiB).
  size_t record_samples_per_launch = size_t(1) << 21;
  size_t per_item = 64;   // light per-pixel or per-record work
  size_t tile_side = 8;   // 2-D launches over the image, tile_side x tile_side pixels a group
};

// OpenCL error codes that mean the device (or the host, for it) ran out of memory.
bool is_out_of_memory(cl_int code);

class GpuContext {
 public:
  explicit GpuContext(const DeviceInfo& device);
  ~GpuContext();  // waits for builds still running ahead
  GpuContext(const GpuContext&) = delete;
  GpuContext& operator=(const GpuContext&) = delete;

  const DeviceInfo& device_info() const { return info_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // The program built from kernels/<file> (its includes resolved) with the given switches; built once per device and
  // set of switches, and kept on disk between runs (GpuContext::cache_file). Throws rcsplat::Error with the build log.
  // Waits for it when build_ahead started it.
  cl::Program& program(const std::string& file, const KernelDefines& defines = {});
  // Starts building that program on a worker thread (at most as many at once as the host has cores) unless it is
  // built or building: the programs a frame will use compile side by side, and beside the frame's first passes, where
  // one after another they took a cold frame's 2.0 s on PoCL and 6-17 s on NVIDIA's compiler. A build that fails
  // reports its error where program() asks for it. RCSPLAT_BUILD_AHEAD=0: each build waits for program() instead.
  void build_ahead(const std::string& file, const KernelDefines& defines = {});

  // Kernel `name` of kernels/<file>, its arguments set by name.
  NamedKernel kernel(const std::string& file, const std::string& name, const KernelDefines& defines = {});
  // A program from source text (its includes resolved from kernels/), for tests of shared kernel code.
  cl::Program& program_from_text(const std::string& label, const std::string& text);

  // Cold builds, for measuring them (`rcsplat bench`): the on-disk cache is neither read nor written, and an unused
  // define carrying `nonce` makes the driver's own cache (PoCL's, NVIDIA's) miss too.
  void use_cold_builds(const std::string& nonce) { cold_build_nonce_ = nonce; }

  // Seconds the caller spent waiting for programs to build (or load from the cache) so far, for the summary: with
  // builds ahead, less than the builds took.
  double program_seconds() const { return program_seconds_; }
  // Each build's own seconds by kernel file ("records.cl"), every set of switches of a file together (`rcsplat
  // bench`'s cold builds by file); builds ahead included, so the sum may exceed the wait.
  std::map<std::string, double> program_seconds_by_file() const;

  const GroupSizes& groups() const { return groups_; }

  // Notes whether a kernel's launch set all its parameters by name in the kernel's own order (NamedKernel::launch;
  // tests/kernel_args_test.cpp reads it through test::PassProbe).
  void note_launch(const std::string& kernel, bool all_in_order) { launched_[kernel] = all_in_order; }

  // A device buffer of `bytes`; running out of device memory (or asking for more than one buffer may hold) throws
  // rcsplat::Error naming `what`, the size asked for and what the device has.
  cl::Buffer buffer(cl_mem_flags flags, size_t bytes, const std::string& what);
  // Makes `buffer` hold at least `count` elements of element_bytes (a pass's buffers, kept across frames): where it
  // holds fewer (or is none), a new one of twice its capacity, or `count` if more, but doubled to at most `most`
  // elements; with keep_contents the old one's elements are copied in, else it is freed before the new one is made.
  // capacity: the elements `buffer` holds.
  void reserve(cl::Buffer& buffer, size_t& capacity, size_t count, size_t element_bytes, const char* what,
               bool keep_contents = false, size_t most = SIZE_MAX);
  template <typename T>
  void reserve(cl::Buffer& buffer, size_t& capacity, size_t count, const char* what, bool keep_contents = false,
               size_t most = SIZE_MAX) {
    reserve(buffer, capacity, count, sizeof(T), what, keep_contents, most);
  }
  // The most device memory this context's buffers may hold at once (--max-device-memory); 0: what the device has.
  void set_memory_budget(uint64_t bytes) { memory_budget_ = bytes; }

  // Device memory in use now and at its peak (a copy; thread-safe). Buffers count until OpenCL frees them (a
  // destructor callback), so the peak is what the device had to hold at once. restart_memory_peak: a new frame's
  // peak starts from what is in use now.
  DeviceMemoryUse memory_use() const;
  void restart_memory_peak();
  struct MemoryLedger;

  template <typename T>
  cl::Buffer upload(const std::vector<T>& data, cl_mem_flags flags = CL_MEM_READ_ONLY, const char* what = "other") {
    // Zero-sized buffers are invalid in OpenCL: keep one element so a kernel argument is always valid.
    size_t bytes = std::max<size_t>(data.size(), 1) * sizeof(T);
    cl::Buffer buffer = this->buffer(flags, bytes, what);
    if (!data.empty()) queue_.enqueueWriteBuffer(buffer, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    return buffer;
  }

  // As upload, into `buffer` where it holds `capacity` elements or more (a pass kept across frames re-uploads small
  // per-frame inputs without a new buffer each time); otherwise into a new buffer, and capacity becomes its size.
  template <typename T>
  void upload_into(cl::Buffer& buffer, size_t& capacity, const std::vector<T>& data, cl_mem_flags flags,
                   const char* what) {
    if (!buffer() || data.size() > capacity) {
      buffer = upload(data, flags, what);
      capacity = std::max<size_t>(data.size(), 1);
    } else if (!data.empty()) {
      queue_.enqueueWriteBuffer(buffer, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    }
  }

  template <typename T>
  std::vector<T> download(const cl::Buffer& buffer, size_t count) {
    std::vector<T> data(count);
    if (count) queue_.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(T), data.data());
    return data;
  }

 private:
  // The programs asked for and built ahead, the kernels built and launched, the buffers made, and another device's
  // group sizes: what tests read and set through test::PassProbe (tests/pass_probe.h).
  friend struct test::PassProbe;
  using ProgramFuture = std::shared_future<std::shared_ptr<cl::Program>>;
  // The program under `key`, built now in this thread unless build_ahead started it: waits for it, timing the wait.
  cl::Program& wait_for(const std::string& key, const std::string& file, const std::function<std::string()>& source,
                        const std::string& options);
  std::shared_ptr<cl::Program> build(const std::string& file, const std::string& source, const std::string& options);
  // The program the on-disk cache holds at cache_file, built for this device; null when there is none or it does
  // not load.
  std::shared_ptr<cl::Program> load_cached(const std::filesystem::path& cache_file, const std::string& options);
  // The build options for a set of switches, and where the on-disk cache keeps what `identity` (everything that
  // changes it) names, with this extension; empty when there is no cache folder or builds are cold.
  std::string build_options(const KernelDefines& defines) const;
  // Everything that changes a program's binary (device, driver, options, resolved source): the on-disk cache's key.
  std::string program_identity(const std::string& source, const std::string& options) const;
  std::filesystem::path cache_file(const std::string& identity, const char* extension) const;

  DeviceInfo info_;
  cl::Context context_;
  cl::CommandQueue queue_;
  GroupSizes groups_;
  // Every program asked for, by "file|options" (or label and text), ready or building; and those build_ahead asked
  // for first. The mutex guards these and program_seconds_by_file_ (builds ahead finish on other threads).
  mutable std::mutex programs_mutex_;
  std::map<std::string, ProgramFuture> programs_;
  std::set<std::string> built_ahead_, asked_for_;
  std::map<std::string, bool> launched_;
  size_t buffers_made_ = 0;
  double program_seconds_ = 0.0;
  std::map<std::string, double> program_seconds_by_file_;
  std::string cold_build_nonce_;
  uint64_t memory_budget_ = 0;
  std::string extra_build_options_;  // RCSPLAT_BUILD_OPTIONS (docs/GPU.md)
  bool parallel_builds_ = true;      // build_ahead on worker threads, else deferred to program()
  std::shared_ptr<MemoryLedger> memory_;  // shared with buffers' destructor callbacks, which may outlive the context
};

// Where kernel sources come from: the embedded copies, or a folder when RCSPLAT_KERNEL_DIR is set (developer mode:
// edit a kernel and rerun without rebuilding).
std::string kernel_source_dir();

// The text of kernels/<file> with every #include "x" replaced by x's text (once per file), framed by #line directives
// so that compiler messages name the original file and line.
std::string resolve_kernel_source(const std::string& file);
// The same for source text given directly, named `label` in messages.
std::string resolve_kernel_text(const std::string& label, const std::string& text);

}  // namespace rcsplat
