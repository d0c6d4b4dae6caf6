// Counter-based random numbers, compiled by both the kernels and the host: the same (a, b, c) gives the same number on
// every device and on the host, so a render is reproducible whatever the work-group order, and host references can
// draw the very samples a kernel drew.
#ifndef RCSPLAT_COUNTER_RANDOM_H
#define RCSPLAT_COUNTER_RANDOM_H
#include "shared_types.h"

inline rc_uint hash_u32(rc_uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

inline float random01(rc_uint a, rc_uint b, rc_uint c) {
  rc_uint h = hash_u32(a ^ hash_u32(b ^ hash_u32(c + 0x9e3779b9u)));
  return (float)(h >> 8) * (1.0f / 16777216.0f);  // 24 bits: strictly below 1
}

#endif
