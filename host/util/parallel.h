// A minimal parallel loop for host-side work (the octree cache, references): indices handed out in chunks to one
// thread per core.
#pragma once
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace rcsplat {

template <typename F>
void parallel_for(size_t count, F&& body, size_t chunk = 64) {
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t start; (start = next.fetch_add(chunk)) < count;)
      for (size_t i = start; i < std::min(count, start + chunk); ++i) body(i);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

// body(begin, end) over consecutive ranges of at most `block` indices, one thread per core: for loops over an image's
// pixels, where a range per call keeps the per-index cost of the call away.
template <typename F>
void parallel_ranges(size_t count, F&& body, size_t block = 16384) {
  parallel_for((count + block - 1) / block, [&](size_t b) { body(b * block, std::min(count, (b + 1) * block)); }, 1);
}

}  // namespace rcsplat
