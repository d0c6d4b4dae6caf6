// The median of a few timings (benchmarks report medians of repeated runs).
#pragma once
#include <algorithm>
#include <vector>

namespace rcsplat {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

}  // namespace rcsplat
