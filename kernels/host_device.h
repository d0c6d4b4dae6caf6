// What lets one header be compiled by both the kernels (OpenCL C) and the host (C++): a three-float vector type, the
// few vector functions the shared math uses, spelled the same on both sides, and the constants both sides use. On the
// device the functions are OpenCL's built-ins; on the host, GLM's (tests/cache_math_test.cpp checks that both give
// the same bits).
#ifndef RCSPLAT_HOST_DEVICE_H
#define RCSPLAT_HOST_DEVICE_H

#define RC_PI 3.14159265358979f
#define RC_INV_PI 0.318309886183791f

// Rec. 709 luminance of linear RGB: the weights written once for the host (util/colour.h) and the kernels
// (sampling.h, guide_clusters.cl), as double literals; RC_FLOAT spells one as a float literal (0.2126 -> 0.2126f).
#define RC_LUMINANCE_R 0.2126
#define RC_LUMINANCE_G 0.7152
#define RC_LUMINANCE_B 0.0722
#define RC_FLOAT_LITERAL(x) x##f
#define RC_FLOAT(x) RC_FLOAT_LITERAL(x)

#ifdef __OPENCL_VERSION__
typedef float3 rc_float3;
#define RC_GLOBAL __global
#define rc_length length
#define rc_distance distance
#define rc_dot dot
#define rc_cross cross
#define rc_fmin fmin
#define rc_fmax fmax
#define rc_fabs fabs
#define rc_sqrt sqrt
#define rc_cos cos
#define rc_sin sin
// Row `row` of three floats starting at p.
#define rc_load3(row, p) vload3(row, p)
#define rc_max_zero(v) max(v, (float3)(0.0f))
#define rc_make3(x, y, z) ((float3)((x), (y), (z)))
#define rc_float_as_int as_int
#define rc_int_as_float as_float
#else
#include <glm/glm.hpp>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
typedef glm::vec3 rc_float3;
#define RC_GLOBAL
inline float rc_length(rc_float3 v) { return glm::length(v); }
inline float rc_distance(rc_float3 a, rc_float3 b) { return glm::distance(a, b); }
inline float rc_dot(rc_float3 a, rc_float3 b) { return glm::dot(a, b); }
inline rc_float3 rc_cross(rc_float3 a, rc_float3 b) { return glm::cross(a, b); }
inline float rc_fmin(float a, float b) { return std::fmin(a, b); }
inline float rc_fmax(float a, float b) { return std::fmax(a, b); }
inline float rc_fabs(float a) { return std::fabs(a); }
inline float rc_sqrt(float a) { return std::sqrt(a); }
inline float rc_cos(float a) { return std::cos(a); }
inline float rc_sin(float a) { return std::sin(a); }
inline rc_float3 rc_load3(int row, const float* p) { return rc_float3(p[3 * row], p[3 * row + 1], p[3 * row + 2]); }
inline rc_float3 rc_max_zero(rc_float3 v) { return glm::max(v, rc_float3(0.0f)); }
inline rc_float3 rc_make3(float x, float y, float z) { return rc_float3(x, y, z); }
inline int rc_float_as_int(float f) { return std::bit_cast<int>(f); }
inline float rc_int_as_float(int i) { return std::bit_cast<float>(i); }
#endif

// Moves a surface point's coordinate p off its surface along the geometric normal's component n (pointing to the side
// the ray leaves to) by a fixed number of float ULPs, so the offset scales with the coordinate's magnitude; near the
// origin, where ULPs vanish, by a small absolute step instead (Wächter and Binder, Ray Tracing Gems, chapter 6). The
// kernels' offset_ray_origin (kernels/sampling.h) and the host's (host/util/ray_offset.h) apply it to each axis.
inline float offset_ray_coordinate(float p, float n) {
  const float near_origin = 1.0f / 32.0f, float_step = 1.0f / 65536.0f, ulp_scale = 256.0f;
  if (rc_fabs(p) < near_origin) return p + float_step * n;
  const int ulps = (int)(ulp_scale * n);
  return rc_int_as_float(rc_float_as_int(p) + (p < 0.0f ? -ulps : ulps));
}

// An orthonormal frame around the unit vector n (Duff et al. 2017, branch-free): the kernels' sampling frame and the
// frame a record's horizon sectors are measured in (kernels/cache_math.h), the same bits on host and device.
inline void tangent_frame(rc_float3 n, rc_float3* t, rc_float3* b) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  *t = rc_make3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = rc_make3(c, sign + n.y * n.y * a, -n.y);
}

#endif
