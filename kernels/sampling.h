// Random numbers, robust ray origins and light sampling helpers shared by the shading kernels.
#ifndef RCSPLAT_SAMPLING_H
#define RCSPLAT_SAMPLING_H
#include "counter_random.h"
#include "host_device.h"

// Moves a surface point off its surface along the geometric normal n (pointing to the side the ray leaves to) by a
// fixed number of float ULPs, so the offset scales with the coordinates' magnitude; near the origin, where ULPs
// vanish, by a small absolute step instead (Wächter and Binder, Ray Tracing Gems, chapter 6).
inline float3 offset_ray_origin(float3 p, float3 n) {
  const float near_origin = 1.0f / 32.0f;
  const float float_step = 1.0f / 65536.0f;
  const float ulp_scale = 256.0f;
  int3 ulps = convert_int3(ulp_scale * n);
  float3 shifted = as_float3(as_int3(p) + select(ulps, -ulps, as_int3(p) < 0));
  return select(shifted, p + float_step * n, fabs(p) < near_origin);
}

inline float luminance(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

inline float3 finite_or_zero(float3 c) {
  return (float3)(isfinite(c.x) ? c.x : 0.0f, isfinite(c.y) ? c.y : 0.0f, isfinite(c.z) ? c.z : 0.0f);
}

// The bin u in [0, 1) falls in, of count bins whose inclusive CDF is cdf[0 .. count - 1] (cdf[count - 1] = 1): the
// first entry above u. Bins of zero width are never chosen.
inline uint cdf_bin(__global const float* cdf, uint count, float u) {
  uint lo = 0, hi = count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (u < cdf[mid]) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

// A cosine-weighted direction about n (frame t, b, n) from uniform (u1, u2): sin^2(theta) = u1, phi = 2 pi u2.
inline float3 cosine_direction(float3 t, float3 b, float3 n, float u1, float u2) {
  float sin_t = sqrt(u1), cos_t = sqrt(1.0f - u1), phi = 2.0f * RC_PI * u2;
  return (cos(phi) * sin_t) * t + (sin(phi) * sin_t) * b + cos_t * n;
}

#endif
