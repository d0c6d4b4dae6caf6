// The path tracer that serves as ground truth and competitor: through the same pixel centres as the G-buffer, a first
// bounce per sample (cosine-weighted at Lambertian pixels, drawn from the BRDF where there is a specular lobe), its hit
// lit directly and the path continued for --bounces in all (kernels/bounce.h): the same integral the cache estimates,
// with the same bounce count.
// Accumulates the indirect radiance and its square per pixel (for the variance).
// Stratified mode draws sample s of a pixel from cell s of a sqrt(spp) x sqrt(spp) grid over the hemisphere.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "bounce.h"
#include "shading_normal.h"
#include "counter_random.h"

__kernel void path_indirect(SCENE_ARGS, GBUFFER_ARGS, __global const float4* see_through, PathParams params,
                            __global float4* sum,
                            __global float4* sum_squares, __global ulong* ray_total) {
  uint pixel = get_global_id(0);
  if (pixel >= (uint)(camera->width * camera->height)) return;
  const uint first_sample = params.first_sample, sample_count = params.sample_count, grid_side = params.grid_side;
  GBufferSample g = gbuffer[pixel];
  if (g.triangle < 0) return;
  float3 p = vload3(0, g.position), n = gbuffer_shading_normal(g), ng = vload3(0, g.geometric_normal);
  float3 albedo = vload3(0, g.albedo);
  float3 origin = offset_ray_origin(p, ng);
  float3 t, b;
  tangent_frame(n, &t, &b);
  uint key = hash_u32(pixel ^ hash_u32(params.seed ^ STREAM_PATH));
  float3 s1 = (float3)(0.0f), s2 = (float3)(0.0f);
  RayTally rays = traced_rays(0u);
#if HAS_SPECULAR_BRDF
  bool specular = g.lobe != LOBE_NONE;
  ShadingFrame frame = shading_frame(n);
  BrdfInputs in = gbuffer_layered_brdf(g, pixel_layers(gbuffer_layers, pixel), n);
  float3 wo = view_local(frame, camera_view_direction(camera, p));
#endif
  for (uint s = first_sample; s < first_sample + sample_count; ++s) {
    float u1 = random01(key, s, 0u), u2 = random01(key, s, 1u);
    if (s < grid_side * grid_side) {  // stratified: this sample's cell of the grid
      u1 = ((float)(s % grid_side) + u1) / (float)grid_side;
      u2 = ((float)(s / grid_side) + u2) / (float)grid_side;
    }
    float3 dir = cosine_direction(t, b, n, u1, u2);
    float3 throughput = albedo;  // cosine-weighted sampling: f cos / pdf = albedo
#if HAS_SPECULAR_BRDF
    if (specular) {
      float3 wi;
      float pdf;
      throughput = brdf_sample(in, wo, random01(key, s, 4u), u1, u2, &wi, &pdf);
      dir = to_world(frame, wi);
    }
#endif
    float3 c = (float3)(0.0f);
    if (dot(dir, ng) > 0.0f && any_positive(throughput)) {
      float r;
      c = throughput * bounce_radiance(SCENE, origin, dir, random01(key, s, 2u), random01(key, s, 3u),
                                       random01(key, s, 5u), path_continuation(key, s, params.bounces), &r,
                                       &rays);
    }
#if HAS_TRANSMISSION
    c *= see_through[pixel].xyz;  // what the glass the camera looked through kept (kernels/gbuffer.cl)
#endif
    s1 += c;
    s2 += c * c;
  }
  sum[pixel] += (float4)(s1, 0.0f);
  sum_squares[pixel] += (float4)(s2, 0.0f);
  atom_add(ray_total, (ulong)rays.cast);
}
