#include "cl/gpu_context.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <regex>
#include <semaphore>
#include <set>
#include <thread>
#include <sstream>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "cl/embedded_kernels.h"
#include "util/atomic_file.h"
#include "util/byte_size.h"
#include "util/error.h"
#include "util/log.h"

#if defined(__SANITIZE_ADDRESS__)
// PoCL 3.1 leaks inside its LLVM compiler (16 bytes and a pass manager's worth) on every build that misses PoCL's own
// cache, as `bench`'s cold builds always do. LeakSanitizer reads these suppressions at exit; they name only the
// driver's libraries, so a leak allocated by rcsplat's code is still reported. OpenCL objects rcsplat forgets to
// release would be allocated inside libpocl and hidden here: the device memory ledger's test guards those.
extern "C" const char* __lsan_default_suppressions() { return "leak:libpocl.so\nleak:libLLVM\n"; }
// PoCL loads each compiled kernel as a shared object and unloads it with its program. LeakSanitizer's tracking of
// dynamic TLS then reads a freed thread-vector entry and crashes ("Tracer caught signal 11") after `bench`'s cold
// builds; without that tracking, static TLS (all of rcsplat's) is still scanned.
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
#endif

namespace rcsplat {
namespace fs = std::filesystem;

namespace {

std::string read_kernel_file(const std::string& file) {
  std::string dir = kernel_source_dir();
  if (dir.empty()) {
    const auto& sources = embedded_kernel_sources();
    auto it = sources.find(file);
    if (it == sources.end()) throw Error("kernel source '" + file + "' is not embedded in this build");
    return it->second;
  }
  std::ifstream in(fs::path(dir) / file, std::ios::binary);
  if (!in) throw Error("kernel source '" + (fs::path(dir) / file).string() + "' cannot be read (RCSPLAT_KERNEL_DIR)");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void append_text(const std::string& label, const std::string& text, std::set<std::string>& seen, std::string& out);

void append_resolved(const std::string& file, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(file).second) return;  // every kernel header is include-once
  append_text(file, read_kernel_file(file), seen, out);
}

void append_text(const std::string& label, const std::string& text, std::set<std::string>& seen, std::string& out) {
  static const std::regex include_line(R"(^\s*#\s*include\s*"([^"]+)\"\s*$)");
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  out += "#line 1 \"kernels/" + label + "\"\n";
  while (std::getline(lines, line)) {
    ++number;
    std::smatch m;
    if (std::regex_match(line, m, include_line)) {
      append_resolved(m[1].str(), seen, out);
      out += "#line " + std::to_string(number + 1) + " \"kernels/" + label + "\"\n";
    } else {
      out += line + "\n";
    }
  }
}

// FNV-1a: a stable 64-bit key for the on-disk cache (std::hash may differ between builds).
uint64_t stable_hash(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

fs::path binary_cache_dir() {
  if (const char* env = std::getenv("RCSPLAT_CACHE_DIR")) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME")) return fs::path(xdg) / "rcsplat";
  if (const char* home = std::getenv("HOME")) return fs::path(home) / ".cache" / "rcsplat";
  return {};
}

std::string build_log(const cl::Program& program, const cl::Device& device) {
  try {
    return program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
  } catch (const cl::Error&) {
    return "(no build log)";
  }
}

}  // namespace

std::string kernel_source_dir() {
  const char* dir = std::getenv("RCSPLAT_KERNEL_DIR");
  return dir && *dir ? dir : "";
}

// The first line of every program: OpenCL C may contract a * b + c into one fused multiply-add where C++ on the host
// (built with -ffp-contract=off, CMakeLists.txt) does not. Off for every kernel, set here once: the math both sides
// compile (kernels/host_device.h, cache_math.h) gives the same bits on both, and the watertight triangle test's edge
// functions (kernels/traverse.h) are evaluated exactly as written, as their mirror images on the neighbour are.
constexpr const char* kProgramPrologue = "#pragma OPENCL FP_CONTRACT OFF\n";

std::string resolve_kernel_source(const std::string& file) {
  std::set<std::string> seen;
  std::string out = kProgramPrologue;
  append_resolved(file, seen, out);
  return out;
}

std::string resolve_kernel_text(const std::string& label, const std::string& text) {
  std::set<std::string> seen;
  std::string out = kProgramPrologue;
  append_text(label, text, seen, out);
  return out;
}

struct GpuContext::MemoryLedger {
  std::mutex mutex;
  DeviceMemoryUse use;
  void add(const std::string& what, size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    use.live_bytes += bytes;
    use.live_by_use[what] += bytes;
    if (use.live_bytes > use.peak_bytes) {
      use.peak_bytes = use.live_bytes;
      use.at_peak_by_use = use.live_by_use;
    }
  }
  void remove(const std::string& what, size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    use.live_bytes -= bytes;
    if ((use.live_by_use[what] -= bytes) == 0) use.live_by_use.erase(what);
  }
};

namespace {

// Buffers counted and not yet freed, by handle: the destructor callback finds its ledger here. A map that is never
// destroyed (callbacks may come while the process exits) and is always reachable (no leak report for buffers a
// driver keeps until exit).
struct CountedBuffer {
  std::shared_ptr<GpuContext::MemoryLedger> ledger;
  std::string what;
  size_t bytes;
};
std::mutex counted_mutex;
auto* const counted_buffers = new std::unordered_map<cl_mem, CountedBuffer>();

void CL_CALLBACK buffer_freed(cl_mem buffer, void*) {
  CountedBuffer freed;
  {
    std::lock_guard<std::mutex> lock(counted_mutex);
    auto it = counted_buffers->find(buffer);
    if (it == counted_buffers->end()) return;
    freed = std::move(it->second);
    counted_buffers->erase(it);
  }
  freed.ledger->remove(freed.what, freed.bytes);
}

}  // namespace

DeviceMemoryUse GpuContext::memory_use() const {
  std::lock_guard<std::mutex> lock(memory_->mutex);
  return memory_->use;
}

void GpuContext::restart_memory_peak() {
  std::lock_guard<std::mutex> lock(memory_->mutex);
  memory_->use.peak_bytes = memory_->use.live_bytes;
  memory_->use.at_peak_by_use = memory_->use.live_by_use;
}

const char* record_trace_name(RecordTrace shape) {
  switch (shape) {
    case RecordTrace::fused: return "fused";
    case RecordTrace::split: return "split";
    case RecordTrace::wavefront: return "wavefront";
  }
  return "?";
}

GpuContext::GpuContext(const DeviceInfo& device) : info_(device), memory_(std::make_shared<MemoryLedger>()) {
  context_ = cl::Context(info_.device);
  queue_ = cl::CommandQueue(context_, info_.device);
  // A GPU keeps a warp or wavefront per group busy only with 32 or more work-items, and its threads in flight only
  // with a ray per work-item; PoCL's CPU device prefers few heavy work-items (measured on the record pass).
  if (info_.device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) {
    groups_.per_record = 32;
    groups_.record_samples_per_item = 1;
    groups_.record_trace = RecordTrace::wavefront;
  }
  // For measuring the record trace's shape on a device (benchmarks/gpu/device_run.sh): every shape gives the same
  // records (RecordKernel.SameRecordsWhateverTheTraceShape), only the time differs.
  if (const char* env = std::getenv("RCSPLAT_RECORD_SAMPLES_PER_ITEM")) {
    char* end = nullptr;
    unsigned long value = std::strtoul(env, &end, 10);
    if (end == env || *end != '\0' || value == 0)
      throw Error(std::string("RCSPLAT_RECORD_SAMPLES_PER_ITEM: expected a positive whole number, got \"") + env +
                  "\"");
    groups_.record_samples_per_item = value;
  }
  if (const char* env = std::getenv("RCSPLAT_RECORD_TRACE")) {  // the same for the trace's shape
    bool known = false;
    for (RecordTrace shape : {RecordTrace::fused, RecordTrace::split, RecordTrace::wavefront})
      if (std::string(env) == record_trace_name(shape)) {
        groups_.record_trace = shape;
        known = true;
      }
    if (!known)
      throw Error(std::string("RCSPLAT_RECORD_TRACE: expected fused, split or wavefront, got \"") + env + "\"");
  }
  // Builds ahead run side by side on worker threads unless RCSPLAT_BUILD_AHEAD=0, which defers each to the program()
  // that asks for it (one build at a time, in the asking thread). On PoCL's CPU device (2-core VM) the cold frame took
  // the same time either way, its wait for builds halved (docs/NOTES.md "2026-11-29, second session"): the device's
  // kernels and its first-launch compiles need the same cores. A GPU leaves them idle.
  if (const char* env = std::getenv("RCSPLAT_BUILD_AHEAD")) {
    if (std::string(env) != "0" && std::string(env) != "1")
      throw Error(std::string("RCSPLAT_BUILD_AHEAD: expected 0 or 1, got \"") + env + "\"");
    parallel_builds_ = std::string(env) == "1";
  }
  // For looking inside a device's compiler (NVIDIA's -cl-nv-verbose prints registers and spills): extra options, and
  // each build's log printed.
  if (const char* extra = std::getenv("RCSPLAT_BUILD_OPTIONS")) extra_build_options_ = extra;
}

// Arguments are bound by name (cl/named_kernel.h): every program keeps its parameters' names and types.
constexpr const char* kBaseBuildOptions = "-cl-std=CL1.2 -cl-kernel-arg-info";

std::string GpuContext::build_options(const KernelDefines& defines) const {
  std::string options = kBaseBuildOptions;
  for (const auto& [name, value] : defines) options += " -D " + name + "=" + value;
  if (!extra_build_options_.empty()) options += " " + extra_build_options_;
  if (!cold_build_nonce_.empty()) options += " -D RCSPLAT_COLD_BUILD=" + cold_build_nonce_;
  return options;
}

std::string GpuContext::program_identity(const std::string& source, const std::string& options) const {
  return info_.platform_name + "|" + info_.name + "|" + info_.driver_version + "|" + options + "|" + source;
}

fs::path GpuContext::cache_file(const std::string& identity, const char* extension) const {
  fs::path dir = binary_cache_dir();
  if (dir.empty() || !cold_build_nonce_.empty()) return {};
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(stable_hash(identity)));
  return dir / (std::string(hex) + extension);
}

GpuContext::~GpuContext() {
  std::vector<ProgramFuture> pending;
  {
    std::lock_guard<std::mutex> lock(programs_mutex_);
    for (const auto& [key, future] : programs_) pending.push_back(future);
  }
  // A build ahead on a worker uses this context's members; one deferred (never asked for) is not started.
  for (const ProgramFuture& future : pending)
    if (future.wait_for(std::chrono::seconds(0)) != std::future_status::deferred) future.wait();
}

namespace {

// The builds ahead that may run at once in this process: one a core, as each compiler build runs on one thread.
class BuildSlot {
 public:
  BuildSlot() { slots().acquire(); }
  ~BuildSlot() { slots().release(); }
  BuildSlot(const BuildSlot&) = delete;
  BuildSlot& operator=(const BuildSlot&) = delete;

 private:
  static std::counting_semaphore<1024>& slots() {
    static std::counting_semaphore<1024> slots(std::clamp<std::ptrdiff_t>(std::thread::hardware_concurrency(), 1, 1024));
    return slots;
  }
};

}  // namespace

cl::Program& GpuContext::program(const std::string& file, const KernelDefines& defines) {
  const std::string options = build_options(defines);
  return wait_for(file + "|" + options, file, [&] { return resolve_kernel_source(file); }, options);
}

void GpuContext::build_ahead(const std::string& file, const KernelDefines& defines) {
  const std::string options = build_options(defines);
  const std::string key = file + "|" + options;
  std::lock_guard<std::mutex> lock(programs_mutex_);
  if (programs_.count(key)) return;
  built_ahead_.insert(key);
  // Deferred: built by program() in the asking thread, as without build_ahead.
  const auto policy = parallel_builds_ ? std::launch::async : std::launch::deferred;
  programs_.emplace(key, std::async(policy, [this, file, options] {
                           BuildSlot slot;
                           return build(file, resolve_kernel_source(file), options);
                         }).share());
}

cl::Program& GpuContext::program_from_text(const std::string& label, const std::string& text) {
  return wait_for(label + "|" + text, label, [&] { return resolve_kernel_text(label, text); }, kBaseBuildOptions);
}

cl::Program& GpuContext::wait_for(const std::string& key, const std::string& file,
                                  const std::function<std::string()>& source, const std::string& options) {
  const auto start = std::chrono::steady_clock::now();
  ProgramFuture future;
  std::promise<std::shared_ptr<cl::Program>> built_here;
  bool build_here = false;
  {
    std::lock_guard<std::mutex> lock(programs_mutex_);
    asked_for_.insert(key);
    auto found = programs_.find(key);
    build_here = found == programs_.end();
    future = build_here ? programs_.emplace(key, built_here.get_future().share()).first->second : found->second;
  }
  if (build_here) {
    try {
      built_here.set_value(build(file, source(), options));
    } catch (...) {
      built_here.set_exception(std::current_exception());
    }
  }
  cl::Program& program = *future.get();  // a failed build's error, each time the program is asked for
  program_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return program;
}

NamedKernel GpuContext::kernel(const std::string& file, const std::string& name, const KernelDefines& defines) {
  return NamedKernel(*this, program(file, defines), name);
}

std::map<std::string, double> GpuContext::program_seconds_by_file() const {
  std::lock_guard<std::mutex> lock(programs_mutex_);
  return program_seconds_by_file_;
}

namespace {

// An exclusive lock on a file beside a cache entry, held while one process compiles it: processes that start
// together (a test suite's shards, a farm's tasks on one node sharing a kernel cache) each wait for the first's
// binary instead of compiling the same program side by side. The kernel drops a dead holder's lock. A lock that
// cannot be taken (a read-only cache) is no lock: the build goes on without it.
class CacheEntryLock {
 public:
  explicit CacheEntryLock(const fs::path& entry) {
    if (entry.empty()) return;
    std::error_code made;
    fs::create_directories(entry.parent_path(), made);
    fd_ = ::open((entry.string() + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~CacheEntryLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock; the file stays for the next process
  }
  CacheEntryLock(const CacheEntryLock&) = delete;
  CacheEntryLock& operator=(const CacheEntryLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace

std::shared_ptr<cl::Program> GpuContext::load_cached(const fs::path& cache_file, const std::string& options) {
  if (cache_file.empty() || !fs::exists(cache_file)) return nullptr;
  std::ifstream in(cache_file, std::ios::binary);
  std::vector<unsigned char> binary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    cl::Program::Binaries binaries{binary};
    auto program = std::make_shared<cl::Program>(context_, std::vector<cl::Device>{info_.device}, binaries);
    program->build({info_.device}, options.c_str());
    return program;
  } catch (const cl::Error&) {
    return nullptr;  // a stale or foreign binary: rebuild from source
  }
}

std::shared_ptr<cl::Program> GpuContext::build(const std::string& file, const std::string& source,
                                               const std::string& options) {
  auto start = std::chrono::steady_clock::now();
  const fs::path cache_file = this->cache_file(program_identity(source, options), ".bin");

  std::shared_ptr<cl::Program> program = load_cached(cache_file, options);
  std::optional<CacheEntryLock> entry_lock;
  if (!program && !cache_file.empty()) {
    entry_lock.emplace(cache_file);
    program = load_cached(cache_file, options);  // another process may have built it while this one waited
  }
  if (!program) {
    program = std::make_shared<cl::Program>(context_, source);
    try {
      program->build({info_.device}, options.c_str());
    } catch (const cl::Error&) {
      throw Error("building kernels/" + file + " (" + options + ") for " + info_.name + " failed:\n" +
                  build_log(*program, info_.device));
    }
    if (!extra_build_options_.empty())
      log_info("build log of kernels/" + file + " (" + options + "):\n" + build_log(*program, info_.device));
    if (!cache_file.empty()) {
      try {
        auto binaries = program->getInfo<CL_PROGRAM_BINARIES>();
        if (!binaries.empty() && !binaries[0].empty())
          // Whole or not at all: another process may read the cache while this one writes it.
          write_file_atomically(cache_file.string(), [&](const std::string& temp) -> std::string {
            std::ofstream out(temp, std::ios::binary);
            out.write(reinterpret_cast<const char*>(binaries[0].data()), std::streamsize(binaries[0].size()));
            return out.flush() ? "" : "cannot be written";
          });
      } catch (const std::exception& e) {
        log_warning(std::string("could not store the compiled kernel in the cache: ") + e.what());
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::lock_guard<std::mutex> lock(programs_mutex_);
  program_seconds_by_file_[file] += seconds;
  return program;
}

bool is_out_of_memory(cl_int code) {
  return code == CL_MEM_OBJECT_ALLOCATION_FAILURE || code == CL_OUT_OF_RESOURCES || code == CL_OUT_OF_HOST_MEMORY ||
         code == CL_INVALID_BUFFER_SIZE;
}

void GpuContext::reserve(cl::Buffer& buffer, size_t& capacity, size_t count, size_t element_bytes, const char* what,
                         bool keep_contents, size_t most) {
  if (buffer() && capacity >= count) return;
  const size_t grown = std::max({count, std::min(2 * capacity, most), size_t(1)});
  if (keep_contents && buffer() && capacity) {
    cl::Buffer bigger = this->buffer(CL_MEM_READ_WRITE, grown * element_bytes, what);
    queue_.enqueueCopyBuffer(buffer, bigger, 0, 0, capacity * element_bytes);
    buffer = bigger;
  } else {
    buffer = cl::Buffer();  // freed before its successor is made
    buffer = this->buffer(CL_MEM_READ_WRITE, grown * element_bytes, what);
  }
  capacity = grown;
}

cl::Buffer GpuContext::buffer(cl_mem_flags flags, size_t bytes, const std::string& what) {
  auto refuse = [&](const std::string& why, const char* advice = "choose another --device") {
    return Error("out of device memory: " + what + " needs " + byte_size(double(bytes), "MiB") + "; " + why +
                 " (device '" + info_.name + "': " + byte_size(double(info_.global_memory), "MiB") + " in all, " +
                 byte_size(double(info_.max_allocation), "MiB") + " in one buffer). Render fewer pixels (--width, " +
                 "--height) or " + advice);
  };
  if (info_.max_allocation && bytes > info_.max_allocation) throw refuse("more than one buffer may hold");
  if (memory_budget_ && memory_use().live_bytes + bytes > memory_budget_)
    throw refuse(byte_size(double(memory_use().live_bytes), "MiB") + " are held already, and the budget is " +
                     byte_size(double(memory_budget_), "MiB") + " (--max-device-memory)",
                 "raise --max-device-memory");
  try {
    cl::Buffer made(context_, flags, bytes);
    ++buffers_made_;
    {
      std::lock_guard<std::mutex> lock(counted_mutex);
      (*counted_buffers)[made()] = CountedBuffer{memory_, what, bytes};
    }
    if (clSetMemObjectDestructorCallback(made(), buffer_freed, nullptr) == CL_SUCCESS) {
      memory_->add(what, bytes);
    } else {  // not counted: the ledger could not learn when it is freed
      std::lock_guard<std::mutex> lock(counted_mutex);
      counted_buffers->erase(made());
    }
    return made;
  } catch (const cl::Error& e) {
    if (is_out_of_memory(e.err())) throw refuse(std::string("the allocation failed (") + e.what() + ")");
    throw;
  }
}

}  // namespace rcsplat
