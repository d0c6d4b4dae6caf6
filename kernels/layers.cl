// The image layers at output resolution (host/passes/layer_pass.h): each output pixel gathers its side x side
// sub-pixels (--pixel-samples side^2; side 1 copies), so the host downloads and fills output-sized layers only. At
// 1920x1080 with four sub-pixels the sub-pixel layers were 2.3 GB a frame, half a GPU frame spent by the host
// (benchmarks/RESULTS.md, issue 13 on the H200). Sums run in a fixed order: same input, same bits.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "shared_types.h"
#include "shading_normal.h"
#include "cache_math.h"

// The first sub-pixel of output pixel (x, y), in a sub-pixel frame side times as wide.
inline size_t first_sub_pixel(int x, int y, uint side, int out_width) {
  return ((size_t)y * side) * ((size_t)out_width * side) + (size_t)x * side;
}

// Each kernel takes the sub-pixel grid's side and the output frame last (LayerPass::launch sets them).
// The surface comes in bands of rows first_row .. first_row + rows - 1 (out holds the band alone: LayerPass keeps one
// band's buffer; the launch may run past the band's rows, rounded up to whole groups).
__kernel void resolve_surface(__global const GBufferSample* gbuffer, __global const float4* direct,
                              __global PixelSurface* out, int first_row, int rows, uint side, int out_width,
                              int out_height) {
  const int x = get_global_id(0), y = first_row + (int)get_global_id(1);
  if (x >= out_width || (int)get_global_id(1) >= rows || y >= out_height) return;
  const size_t first = first_sub_pixel(x, y, side, out_width), row = (size_t)out_width * side;
  float3 emission = 0.0f, light = 0.0f, albedo = 0.0f, normal = 0.0f;
  float shadow_rays = 0.0f;
  uint lobe_counts = 0;
  for (uint j = 0; j < side; ++j)
    for (uint i = 0; i < side; ++i) {
      const size_t k = first + j * row + i;
      const GBufferSample g = gbuffer[k];
      emission += vload3(0, g.emission);
      albedo += vload3(0, g.albedo);
      normal += gbuffer_shading_normal(g);
      light += direct[k].xyz;
      shadow_rays += direct[k].w;
      const uint shift = lobe_count_shift(g.lobe);
      if (g.triangle >= 0 && shift < 32u) lobe_counts += 1u << shift;
    }
  const float inv = 1.0f / (float)(side * side);
  const GBufferSample centre = gbuffer[first + (side / 2) * row + side / 2];
  PixelSurface s;
  vstore3(emission * inv, 0, s.emission);
  vstore3(light * inv, 0, s.direct);
  vstore3(albedo * inv, 0, s.albedo);
  vstore3(normal * inv, 0, s.normal);
  vstore3(vload3(0, centre.position), 0, s.position);
  s.shadow_rays = shadow_rays;
  s.triangle = centre.triangle;
  s.depth = centre.depth;
  s.pad = 0;
  s.lobe_counts = lobe_counts;
  out[(size_t)(y - first_row) * out_width + x] = s;
}

// The colour before indirect light (emission + direct, RGB; A 0) of a frame that brings back its colour alone
// (RenderSettings::color_only with path tracing or direct light alone): the same float operations as resolve_surface's
// means and the host's sum of them, so the same bits as a frame with every layer.
__kernel void resolve_direct_colour(__global const GBufferSample* gbuffer, __global const float4* direct,
                                    __global float4* out, uint side, int out_width, int out_height) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= out_width || y >= out_height) return;
  const size_t first = first_sub_pixel(x, y, side, out_width), row = (size_t)out_width * side;
  float3 emission = 0.0f, light = 0.0f;
  for (uint j = 0; j < side; ++j)
    for (uint i = 0; i < side; ++i) {
      const size_t k = first + j * row + i;
      emission += vload3(0, gbuffer[k].emission);
      light += direct[k].xyz;
    }
  const float inv = 1.0f / (float)(side * side);
  const float3 emission_mean = emission * inv, direct_mean = light * inv;
  out[(size_t)y * out_width + x] = (float4)(emission_mean + direct_mean, 0.0f);
}

// scale 1 / side^2: the sub-pixels' mean; 1: their sum.
__kernel void resolve_rgba(__global const float4* source, float scale, __global float4* out, uint side,
                           int out_width, int out_height) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= out_width || y >= out_height) return;
  const size_t first = first_sub_pixel(x, y, side, out_width), row = (size_t)out_width * side;
  float4 sum = 0.0f;
  for (uint j = 0; j < side; ++j)
    for (uint i = 0; i < side; ++i) sum += source[first + j * row + i];
  out[(size_t)y * out_width + x] = sum * scale;
}

// The cache's own layers: (mean records reaching a sub-pixel, records sitting in the pixel, sub-pixels with geometry
// that no record reached (irradiance weight 0), 0).
__kernel void resolve_record_counts(__global const GBufferSample* gbuffer, __global const float4* irradiance,
                                    __global const uint* records_per_pixel, __global const int* record_at_pixel,
                                    __global float4* out, uint side, int out_width, int out_height) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= out_width || y >= out_height) return;
  const size_t first = first_sub_pixel(x, y, side, out_width), row = (size_t)out_width * side;
  float reaching = 0.0f, sitting = 0.0f, uncovered = 0.0f;
  for (uint j = 0; j < side; ++j)
    for (uint i = 0; i < side; ++i) {
      const size_t k = first + j * row + i;
      reaching += (float)records_per_pixel[k];
      sitting += record_at_pixel[k] >= 0 ? 1.0f : 0.0f;
      uncovered += gbuffer[k].triangle >= 0 && irradiance[k].w == 0.0f ? 1.0f : 0.0f;
    }
  out[(size_t)y * out_width + x] = (float4)(reaching / (float)(side * side), sitting, uncovered, 0.0f);
}

// Counts for the summary of a frame whose layers stay on the device (RenderSettings::color_only), summed as whole
// numbers: the same bits whatever order work items run in, and the same numbers the host adds up from the downloaded
// layers. One work item per sub-pixel; a work-group (LAYER_COUNT_GROUP items) adds its counts in local memory and then
// once to the frame's: on a GPU, one global atomic per sub-pixel on one address would queue millions of updates a
// 1080p frame.

// sums[0 .. LOBE_KINDS - 1]: the sub-pixels with geometry of each lobe (as resolve_surface packs them).
__kernel void count_lobes(__global const GBufferSample* gbuffer, uint sub_pixels, __global ulong* sums) {
  __local uint counts[LOBE_KINDS];
  const size_t k = get_global_id(0);
  const uint item = get_local_id(0);
  for (uint lobe = item; lobe < LOBE_KINDS; lobe += get_local_size(0)) counts[lobe] = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (k < sub_pixels && gbuffer[k].triangle >= 0 && lobe_count_shift(gbuffer[k].lobe) < 32u)
    atomic_inc(counts + gbuffer[k].lobe);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint lobe = item; lobe < LOBE_KINDS; lobe += get_local_size(0))
    if (counts[lobe]) atom_add(sums + lobe, (ulong)counts[lobe]);
}

// sums[0] += the A channel of every sub-pixel, a whole number there (shadow rays, a pass's rays).
__kernel void sum_alpha(__global const float4* source, uint sub_pixels, __global ulong* sums) {
  __local uint sum;
  const size_t k = get_global_id(0);
  if (get_local_id(0) == 0) sum = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  const uint a = k < sub_pixels ? (uint)source[k].w : 0u;
  if (a) atomic_add(&sum, a);
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0 && sum) atom_add(sums, (ulong)sum);
}

// sums[0] += the sub-pixels with geometry that no record reached (irradiance weight 0), as resolve_record_counts
// counts them.
__kernel void count_uncovered(__global const GBufferSample* gbuffer, __global const float4* irradiance,
                              uint sub_pixels, __global ulong* sums) {
  __local uint count;
  const size_t k = get_global_id(0);
  if (get_local_id(0) == 0) count = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (k < sub_pixels && gbuffer[k].triangle >= 0 && irradiance[k].w == 0.0f) atomic_inc(&count);
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0 && count) atom_add(sums, (ulong)count);
}

// sums[0] += the records whose reach sits at the lower screen-space clamp, sums[1] += those at the upper one, as the
// host's count_clamped_radii (host/render/placement.cpp) counts them (reach_clamp_side): so that a frame whose records
// stay on the device still reports them. One work item per record.
__kernel void count_clamped_reaches(__global const CacheRecord* records, uint record_count, float accuracy,
                                    float min_reach_pixels, float max_reach_pixels, __global ulong* sums) {
  __local uint at_min, at_max;
  const size_t k = get_global_id(0);
  if (get_local_id(0) == 0) at_min = at_max = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (k < record_count) {
    const int side =
        reach_clamp_side(accuracy, records[k].radius, records[k].pixel_size, min_reach_pixels, max_reach_pixels);
    if (side < 0) atomic_inc(&at_min);
    else if (side > 0) atomic_inc(&at_max);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0) {
    if (at_min) atom_add(sums, (ulong)at_min);
    if (at_max) atom_add(sums + 1, (ulong)at_max);
  }
}
