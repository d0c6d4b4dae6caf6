// Host twin of the kernels' counter-based random numbers (kernels/sampling.h): the same (a, b, c) gives the same
// number on the host and on every device, so host references can draw the samples a kernel drew.
#pragma once
#include <cstdint>

namespace rcsplat {

inline uint32_t hash_u32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

inline float random01(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t h = hash_u32(a ^ hash_u32(b ^ hash_u32(c + 0x9e3779b9u)));
  return float(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace rcsplat
