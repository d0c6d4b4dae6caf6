// Samples in rounds over output pixels (kernels/glossy.cl, kernels/direct.cl; the host's side:
// host/passes/sample_rounds.h): the sub-pixels of an output pixel, a round's list of output pixels, and a nested
// stratification that stays stratified whatever count a pixel's rounds end with.
#ifndef RCSPLAT_PIXEL_ROUNDS_H
#define RCSPLAT_PIXEL_ROUNDS_H
#include "counter_random.h"
#include "sampling.h"
#include "shared_types.h"

// Point t of a nested stratification of the unit square, scrambled by key: points 0..3 lie one in each quadrant,
// 0..15 one in each cell of a 4 x 4 grid, 0..63 of an 8 x 8 one, up to 16 x 16; each alone is uniform over the square.
// t's base-4 digits choose a child cell level by level, each level's choice permuted by a hash of the cell it is in
// (an Owen-style scramble), so a pixel stays stratified however many samples its rounds end with.
#define NESTED_STRATA_LEVELS 4u
inline float2 nested_stratum_point(uint t, uint key, float u1, float u2) {
  uint x = 0u, y = 0u;
  for (uint level = 0u; level < NESTED_STRATA_LEVELS; ++level) {
    const uint cell = t & ((1u << (2u * level)) - 1u);  // the digits that chose the cells above
    const uint child = ((t >> (2u * level)) & 3u) ^ (hash_u32(key ^ hash_u32(cell * 8u + level)) & 3u);
    x = 2u * x + (child & 1u);
    y = 2u * y + (child >> 1u);
  }
  const float cells = (float)(1u << NESTED_STRATA_LEVELS);
  return (float2)(((float)x + u1) / cells, ((float)y + u2) / cells);
}

// The sub-pixels of an output pixel: the G-buffer is an s-times larger frame (s = sub_pixel_side, row-major), and
// sub-pixel `sub` (0 .. s^2 - 1) of output pixel o is row sub / s, column sub % s of o's s x s block.
inline uint sub_pixels_per_pixel(__global const CameraParams* camera) {
  const uint side = (uint)max(camera->sub_pixel_side, 1);
  return side * side;
}
inline uint sub_pixel_of(__global const CameraParams* camera, uint output_pixel, uint sub) {
  const uint side = (uint)max(camera->sub_pixel_side, 1), width = (uint)camera->width / side;
  return ((output_pixel / width) * side + sub / side) * (uint)camera->width + (output_pixel % width) * side + sub % side;
}
// A round's output pixel number i: from its list (listed 1), or every output pixel in order.
inline uint listed_output_pixel(uint listed, __global const uint* pixel_list, uint i) {
  return listed ? pixel_list[i] : i;
}

// An output pixel's error estimate from its sub-pixels' samples: their luminance moments pooled (a sub-pixel may have
// one sample), and the sum over the sub-pixels of m / k^2, m samples of luminance y making an estimate of k samples'
// mean (k = m, or fewer where a chunk's samples are weighed together), which times Var(y) is that estimate's variance.
typedef struct {
  float sum_y, sum_y2, samples, spread, pooled;
} PooledMoments;

inline void pool_sub_pixel(PooledMoments* p, float4 moments, float estimate_samples) {
  p->sum_y += moments.x;
  p->sum_y2 += moments.y;
  p->samples += moments.z;
  p->spread += moments.z / (estimate_samples * estimate_samples);
  p->pooled += 1.0f;
}

// (the variance of the output pixel's sampled light, its s^2 sub-pixels' mean; the sub-pixels pooled), or 0 sub-pixels
// where fewer than 2 samples leave the variance unknown.
inline float2 pooled_variance(PooledMoments p, uint sub_pixels) {
  if (!(p.samples >= 2.0f)) return (float2)(0.0f);
  const float var_y = fmax(p.sum_y2 - p.sum_y * p.sum_y / p.samples, 0.0f) / (p.samples - 1.0f);
  const float s2 = (float)sub_pixels;
  return (float2)(var_y * p.spread / (s2 * s2), p.pooled);
}

// What an error kernel writes for an output pixel (host/passes/sample_rounds.h): (the variance of its sampled light,
// its other light, the sub-pixels pooled, its sampled light), other and sampled summed over its s^2 sub-pixels.
inline float4 pixel_error_estimate(PooledMoments pool, uint sub_pixels, float other, float sampled) {
  const float2 variance = pooled_variance(pool, sub_pixels);
  const float s2 = (float)sub_pixels;
  return (float4)(finite_or_zero((float3)(variance.x, other / s2, sampled / s2)), variance.y).xywz;
}

#endif
