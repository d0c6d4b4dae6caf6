// What fresh host memory costs (benchmarks/RESULTS.md, "Issue 13, thirteenth step"): 16 vectors of 33 MB made and
// zeroed, three times in one process, with 4 KB pages or with transparent huge pages asked for (madvise), then written
// again. Plain C++, no rcsplat code:   build/benchmarks/fresh_pages && build/benchmarks/fresh_pages huge
#include <sys/mman.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Sizes `v` to n zeroed floats; with `huge`, asks for transparent huge pages before the first touch.
void make(std::vector<float>& v, size_t n, bool huge) {
  v.reserve(n);
  if (huge) {
    const uintptr_t page = 4096;
    const uintptr_t begin = (uintptr_t(v.data()) + page - 1) & ~(page - 1), end = uintptr_t(v.data() + n) & ~(page - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
  v.resize(n);
}

}  // namespace

int main(int argc, char**) {
  const bool huge = argc > 1;
  const size_t floats = size_t(33) << 18;  // 33 MiB
  for (int round = 0; round < 3; ++round) {
    auto t = Clock::now();
    std::vector<std::vector<float>> blocks(16);
    for (auto& v : blocks) make(v, floats, huge);
    const double made = seconds_since(t);
    t = Clock::now();
    for (auto& v : blocks) std::memset(v.data(), 1, v.size() * sizeof(float));
    std::printf("%s pages: made and zeroed %.3f s, written again %.3f s (%zu MiB)\n", huge ? "huge" : "4 KB", made,
                seconds_since(t), blocks.size() * floats * sizeof(float) >> 20);
  }
}
