// The splat (docs/ALGORITHM.md section 3): each record adds w * E_k(P) and w to every pixel of its screen footprint where its
// full Ward weight exceeds 1/a, into 64-bit fixed-point sums that come out the same whatever order records land in.
// Then the normalisation divides (kernels/compose.cl composes).
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "footprint.h"
#include "shading_normal.h"
#include "sampling.h"
#include "scene_args.h"

__kernel void clear_accumulators(GBUFFER_ARGS, __global long* sums, __global uint* counts) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  vstore4((long4)(0), i, sums);
  counts[i] = 0u;
}

// The largest irradiance component over all records, as float bits (positive floats order like their bits).
__kernel void max_record_irradiance(__global const CacheRecord* records, SplatParams params, __global uint* max_bits) {
  uint i = params.first_record + get_global_id(0);
  if (get_global_id(0) >= params.record_count) return;
  float3 e = vload3(0, records[i].irradiance);
  atomic_max(max_bits, as_uint(fmax(fmax(e.x, e.y), fmax(e.z, 0.0f))));
}

// One work-item per record, visiting its footprint.
__kernel void splat_records(GBUFFER_ARGS, __global const CacheRecord* records, SplatParams params,
                            __global long* sums, __global uint* counts) {
  if (get_global_id(0) >= params.record_count) return;
  uint k = params.first_record + get_global_id(0);
  __global const CacheRecord* rec = records + k;
  float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal);
  float radius = rec->radius;
  float3 tk, bk;
  tangent_frame(nk, &tk, &bk);
  PixelRect rect = sphere_footprint(camera, pk, params.accuracy * radius);
  float to_fixed = FIXED_POINT_ONE / params.irradiance_scale;
  for (int y = rect.y0; y <= rect.y1; ++y) {
    for (int x = rect.x0; x <= rect.x1; ++x) {
      uint pixel = (uint)(y * camera->width + x);
      __global const GBufferSample* g = gbuffer + pixel;
      if (g->triangle < 0) continue;
      float3 p = vload3(0, g->position), n = vload3(0, g->normal);
      float w = ward_weight(p, n, pk, nk, radius);
      if (!record_reaches(rec, tk, bk, w, params.accuracy, p, n, pk, nk, radius)) continue;
      // Weighed by the interpolated normal, turned to the normal map's by the rotation gradient.
      float3 e = fmin(extrapolated_irradiance(rec, p, gbuffer_shading_normal(*g)), (float3)(params.irradiance_scale));
      add_weighted_fixed_point(sums + 4 * (size_t)pixel, w, e, to_fixed);
      atomic_inc(counts + pixel);
    }
  }
}

// Normalisation: E = sum(w E) / sum(w), with the weight sum in A (0 where no usable record reached the pixel: no
// indirect light there). kernels/compose.cl turns it into the pixel's indirect light.
__kernel void resolve_indirect(GBUFFER_ARGS, __global const long* sums, SplatParams params,
                               __global float4* irradiance_out) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  irradiance_out[i] = normalized_fixed_point(vload4(i, sums), params.irradiance_scale);
}

// Anti-aliasing places records one output pixel apart (CacheSettings::finest_spacing_pixels), so a sub-pixel may be
// left where no record reaches at the accuracy: a sliver along an edge. It takes the irradiance of the record that
// record_for_uncovered_pixel (cache_math.h) chooses among those sitting within `window` sub-pixels, with no weight
// threshold (the bias stays within such slivers); its weight goes to .w so that it counts as covered.
__kernel void fill_uncovered(GBUFFER_ARGS, __global const CacheRecord* records, __global const int* record_at_pixel,
                             int window, __global float4* irradiance_out, __global uint* filled) {
  uint i = get_global_id(0);
  const int width = camera->width, height = camera->height;
  if (i >= (uint)(width * height)) return;
  if (gbuffer[i].triangle < 0 || irradiance_out[i].w > 0.0f) return;
  float3 p = vload3(0, gbuffer[i].position), n = vload3(0, gbuffer[i].normal);
  float w;
  int chosen = record_for_uncovered_pixel(records, record_at_pixel, width, height, (int)i % width, (int)i / width,
                                          window, p, n, &w);
  if (chosen < 0) return;
  irradiance_out[i] = (float4)(vload3(0, records[chosen].irradiance), fmax(w, FLT_MIN));
  atomic_inc(filled);
}
