// Random numbers, robust ray origins and light sampling helpers shared by the shading kernels.
#ifndef RCSPLAT_SAMPLING_H
#define RCSPLAT_SAMPLING_H
#include "counter_random.h"
#include "host_device.h"

// A surface point moved off its surface along the geometric normal n (host_device.h offset_ray_coordinate, per axis).
inline float3 offset_ray_origin(float3 p, float3 n) {
  return (float3)(offset_ray_coordinate(p.x, n.x), offset_ray_coordinate(p.y, n.y), offset_ray_coordinate(p.z, n.z));
}

inline float luminance(float3 c) {
  return RC_FLOAT(RC_LUMINANCE_R) * c.x + RC_FLOAT(RC_LUMINANCE_G) * c.y + RC_FLOAT(RC_LUMINANCE_B) * c.z;
}

// Whether any channel of c is above 0 (a light, a weight or a throughput that still carries something).
inline bool any_positive(float3 c) { return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f; }

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
