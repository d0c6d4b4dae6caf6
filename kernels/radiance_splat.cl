// The radiance splat (Gautron et al. 2005 with Křivánek et al.'s radiance caching): each radiance record adds
// w * L_o and w to every pixel of its footprint whose lobe it caches (LOBE_HSH) and where its Ward weight exceeds
// 1/a, with L_o the pixel's own lobe, for its own view, dotted with the record's coefficients moved to the pixel
// (kernels/hsh_frame.h); 64-bit fixed-point sums, the same whatever order records land in. Then the normalisation.
// Also the G-buffer copy placement works on: only the radiance-cached pixels see geometry there.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "brdf_frame.h"
#include "shading_normal.h"
#include "footprint.h"
#include "hsh_frame.h"
#include "scene_args.h"

__kernel void keep_radiance_cached_pixels(GBUFFER_ARGS, __global GBufferSample* kept) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[i];
  if (g.lobe != LOBE_HSH) g.triangle = -1;
  kept[i] = g;
}

__kernel void clear_radiance_sums(GBUFFER_ARGS, __global long* sums) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  vstore4((long4)(0), i, sums);
}

// The pixel's lobe coefficients at its view angle, linear between the table's bins (cos(theta_o) at bin centres).
inline void lobe_at_view(__global const float* table, int row, int angle_count, int n2, float cos_o, float* a,
                         float* b) {
  float x = clamp(cos_o * (float)angle_count - 0.5f, 0.0f, (float)(angle_count - 1));
  int i0 = min((int)x, angle_count - 1), i1 = min(i0 + 1, angle_count - 1);
  float f = x - (float)i0;
  __global const float* r0 = table + (size_t)(row * angle_count + i0) * (size_t)(2 * n2);
  __global const float* r1 = table + (size_t)(row * angle_count + i1) * (size_t)(2 * n2);
  for (int k = 0; k < n2; ++k) {
    a[k] = mix(r0[k], r1[k], f);
    b[k] = mix(r0[n2 + k], r1[n2 + k], f);
  }
}

// Record r's reflected radiance at pixel g (a radiance-cached one, its table row `row`): the pixel's own lobe for its
// own view, dotted with the record's coefficients moved to the pixel; (tk, bk): the record's frame.
inline float3 record_lobe_radiance(__global const CameraParams* camera, __global const GBufferSample* g,
                                   __global const float* block, int order, float3 pk, float3 nk, float3 tk, float3 bk,
                                   __global const float* lobe_table, int row, RadianceSplatParams params) {
  const int n2 = order * order;
  float lobe_a[HSH_MAX_COEFFICIENTS], lobe_b[HSH_MAX_COEFFICIENTS];
  float3 p = vload3(0, g->position), n = gbuffer_shading_normal(*g);
  float3 view = camera_view_direction(camera, p);
  HshFrameChange change = hsh_frame_change(nk, tk, bk, n, view);
  float3 delta = p - pk;
  lobe_at_view(lobe_table, row, (int)params.angle_count, n2, fmax(dot(n, view), 0.0f), lobe_a, lobe_b);
  float3 c0, c1;
  specular_fresnel_terms(gbuffer_brdf(*g), &c0, &c1);
  float3 radiance = hsh_reflected(block, order, dot(delta, tk), dot(delta, bk), change, lobe_a, lobe_b, c0, c1);
  // Truncation rings: a lobe reflects neither less than nothing nor more than the brightest stratum.
  return clamp(finite_or_zero(radiance), 0.0f, params.radiance_scale);
}

inline __global const float* record_coefficients(__global const float* coefficients, uint r, int order) {
  return coefficients + (size_t)r * (size_t)(HSH_RECORD_PARTS * 3 * order * order);
}

// One work-item per record, visiting its footprint.
__kernel void splat_radiance(GBUFFER_ARGS, __global const CacheRecord* records, __global const float* coefficients,
                             __global const float* lobe_table, __global const int* table_row_of_material,
                             RadianceSplatParams params, __global long* sums) {
  uint r = get_global_id(0);
  if (r >= params.record_count) return;
  __global const CacheRecord* rec = records + r;
  const int order = (int)params.order;
  __global const float* block = record_coefficients(coefficients, r, order);
  float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal);
  float3 tk, bk;
  tangent_frame(nk, &tk, &bk);  // the record's HSH frame and its horizon's
  float radius = rec->radius;
  PixelRect rect = sphere_footprint(camera, pk, params.accuracy * radius);
  float to_fixed = FIXED_POINT_ONE / params.radiance_scale;
  for (int y = rect.y0; y <= rect.y1; ++y) {
    for (int x = rect.x0; x <= rect.x1; ++x) {
      uint pixel = (uint)(y * camera->width + x);
      __global const GBufferSample* g = gbuffer + pixel;
      if (g->triangle < 0 || g->lobe != LOBE_HSH) continue;
      int row = table_row_of_material[g->material];
      if (row < 0) continue;
      float3 p = vload3(0, g->position), n = vload3(0, g->normal);
      float w = ward_weight(p, n, pk, nk, radius);
      if (!record_reaches(rec, tk, bk, w, params.accuracy, p, n, pk, nk, radius)) continue;
      float3 radiance = record_lobe_radiance(camera, g, block, order, pk, nk, tk, bk, lobe_table, row, params);
      add_weighted_fixed_point(sums + 4 * (size_t)pixel, w, radiance, to_fixed);
    }
  }
}

// L_o = sum(w L_o) / sum(w) (RGB) and the weight sum (A); zero where no radiance record reached.
__kernel void resolve_radiance(GBUFFER_ARGS, __global const long* sums, RadianceSplatParams params,
                               __global float4* lobe_out) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  lobe_out[i] = normalized_fixed_point(vload4(i, sums), params.radiance_scale);
}

// Radiance records are placed one output pixel apart too: a radiance-cached sub-pixel no record reached takes the
// lobe radiance of the record record_for_uncovered_pixel (cache_math.h) chooses within `window` sub-pixels
// (record_at_pixel: the radiance placement's map), as the irradiance splat's fill_uncovered does.
__kernel void fill_uncovered_radiance(GBUFFER_ARGS, __global const CacheRecord* records,
                                      __global const float* coefficients, __global const float* lobe_table,
                                      __global const int* table_row_of_material, __global const int* record_at_pixel,
                                      int window, RadianceSplatParams params, __global float4* lobe_out,
                                      __global uint* filled) {
  uint i = get_global_id(0);
  const int width = camera->width, height = camera->height;
  if (i >= (uint)(width * height)) return;
  __global const GBufferSample* g = gbuffer + i;
  if (g->triangle < 0 || g->lobe != LOBE_HSH || lobe_out[i].w > 0.0f) return;
  int row = table_row_of_material[g->material];
  if (row < 0) return;
  float w;
  int k = record_for_uncovered_pixel(records, record_at_pixel, width, height, (int)i % width, (int)i / width, window,
                                     vload3(0, g->position), vload3(0, g->normal), &w);
  if (k < 0) return;
  __global const CacheRecord* rec = records + k;
  float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal);
  float3 tk, bk;
  tangent_frame(nk, &tk, &bk);
  const int order = (int)params.order;
  float3 radiance = record_lobe_radiance(camera, g, record_coefficients(coefficients, (uint)k, order), order, pk, nk,
                                         tk, bk, lobe_table, row, params);
  lobe_out[i] = (float4)(radiance, fmax(w, FLT_MIN));
  atomic_inc(filled);
}
