// The splat (ALGORITHM.md section 3): each record adds w * E_k(P) and w to every pixel of its screen footprint where its
// full Ward weight exceeds 1/a, into 64-bit fixed-point sums that come out the same whatever order records land in.
// Then the normalisation divides, and the composition adds the indirect light to emission and direct light.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "cache.h"
#include "sampling.h"

// Fixed-point unit 2^48: w <= MAX_RECORD_WEIGHT = 1e3 and w * E / irradiance_scale <= w, so one contribution is below
// 2^58. Only a record's own pixel can bring w above 1 / (a / MAX spacing) (about 70 at the defaults: other pixels are
// at least a pixel footprint away), so a sum would need hundreds of records on one pixel to reach 2^63. Resolution:
// an irradiance 1e-9 of the frame's largest still has about 2^18 units, so dark corners beside HDR light keep
// their precision.
#define FIXED_POINT_ONE 281474976710656.0f

__kernel void clear_accumulators(__global long* sums, __global uint* counts, uint pixel_count) {
  uint i = get_global_id(0);
  if (i >= pixel_count) return;
  vstore4((long4)(0), i, sums);
  counts[i] = 0u;
}

// The largest irradiance component over all records, as float bits (positive floats order like their bits).
__kernel void max_record_irradiance(__global const CacheRecord* records, uint record_count, __global uint* max_bits) {
  uint i = get_global_id(0);
  if (i >= record_count) return;
  float3 e = vload3(0, records[i].irradiance);
  atomic_max(max_bits, as_uint(fmax(fmax(e.x, e.y), fmax(e.z, 0.0f))));
}

// One work-item per record, visiting its footprint.
__kernel void splat_records(__global const CacheRecord* records, SplatParams params,
                            __global const GBufferSample* gbuffer, __global const CameraParams* camera,
                            __global long* sums, __global uint* counts) {
  if (get_global_id(0) >= params.record_count) return;
  uint k = params.first_record + get_global_id(0);
  __global const CacheRecord* rec = records + k;
  float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal);
  float radius = rec->radius;
  PixelRect rect = sphere_footprint(camera, pk, params.accuracy * radius);
  float to_fixed = FIXED_POINT_ONE / params.irradiance_scale;
  for (int y = rect.y0; y <= rect.y1; ++y) {
    for (int x = rect.x0; x <= rect.x1; ++x) {
      uint pixel = (uint)(y * camera->width + x);
      __global const GBufferSample* g = gbuffer + pixel;
      if (g->triangle < 0) continue;
      float3 p = vload3(0, g->position), n = vload3(0, g->normal);
      float w = ward_weight(p, n, pk, nk, radius);
      if (!record_usable(w, params.accuracy, p, n, pk, nk, radius)) continue;
      float3 e = fmin(extrapolated_irradiance(rec, p, n), (float3)(params.irradiance_scale));
      float3 we = (w * to_fixed) * e;
      __global long* sum = sums + 4 * (size_t)pixel;
      atom_add(sum + 0, convert_long(we.x));
      atom_add(sum + 1, convert_long(we.y));
      atom_add(sum + 2, convert_long(we.z));
      atom_add(sum + 3, convert_long(w * FIXED_POINT_ONE));
      atomic_inc(counts + pixel);
    }
  }
}

// Normalisation and composition: E = sum(w E) / sum(w); indirect = albedo / pi * E; color = emission + direct +
// indirect. Uncovered pixels (no usable record) get no indirect light and coverage 0.
__kernel void resolve_indirect(__global const long* sums, SplatParams params, __global const GBufferSample* gbuffer,
                               __global const float4* direct, uint pixel_count, __global float4* irradiance_out,
                               __global float4* indirect_out, __global float4* color_out) {
  uint i = get_global_id(0);
  if (i >= pixel_count) return;
  long4 s = vload4(i, sums);
  GBufferSample g = gbuffer[i];
  float3 e = (float3)(0.0f);
  float weight = (float)s.w / FIXED_POINT_ONE;
  if (s.w > 0) e = convert_float3(s.xyz) / (float)s.w * params.irradiance_scale;
  e = finite_or_zero(e);
  float3 indirect = vload3(0, g.albedo) * RC_INV_PI * e;
  irradiance_out[i] = (float4)(e, weight);
  indirect_out[i] = (float4)(indirect, s.w > 0 ? 1.0f : 0.0f);
  color_out[i] = (float4)(finite_or_zero(vload3(0, g.emission) + direct[i].xyz + indirect), 1.0f);
}
