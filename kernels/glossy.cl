// The specular part of the indirect light at pixels whose lobe is glossy (LOBE_GLOSSY), by sampling the lobe alone:
// the cache's irradiance carries the diffuse base (kernels/splat.cl), and a glossy lobe is too narrow for irradiance
// to stand in for the light it reflects. Each sample reflects the view about a visible normal of the GGX lobe
// (Heitz 2018), drawn from a grid_side x grid_side grid, and weighs the directly lit radiance its ray finds
// (kernels/bounce.h) by F G2 / G1. Writes RGB = the mean, A = the rays the pixel cast. With SAMPLE_HSH_LOBES the
// radiance-cacheable lobes (LOBE_HSH) are sampled too, for cache methods that do not radiance-cache them.
#include "bounce.h"

__kernel void glossy_indirect(SCENE_ARGS, GBUFFER_ARGS, PathParams params, __global float4* glossy_out) {
  uint pixel = get_global_id(0);
  if (pixel >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[pixel];
  bool sampled = g.lobe == LOBE_GLOSSY || (SAMPLE_HSH_LOBES && g.lobe == LOBE_HSH);
  if (g.triangle < 0 || !sampled) {
    glossy_out[pixel] = (float4)(0.0f);
    return;
  }
  float3 p = vload3(0, g.position), ng = vload3(0, g.geometric_normal);
  ShadingFrame frame = shading_frame(vload3(0, g.normal));
  BrdfInputs in = gbuffer_brdf(g);
  float3 wo = view_local(frame, camera_view_direction(camera, p));
  float3 origin = offset_ray_origin(p, ng);
  uint key = hash_u32(pixel ^ hash_u32(params.seed ^ 0x2c1b3c6du));
  const uint side = params.grid_side, count = params.sample_count;
  float3 sum = (float3)(0.0f);
  uint rays = 0;
  for (uint s = 0; s < count; ++s) {
    float u1 = random01(key, s, 0u), u2 = random01(key, s, 1u);
    if (s < side * side) {
      u1 = ((float)(s % side) + u1) / (float)side;
      u2 = ((float)(s / side) + u2) / (float)side;
    }
    float3 h = ggx_sample_visible_normal(wo, in.alpha, u1, u2);
    float3 wi = 2.0f * dot(wo, h) * h - wo;
    if (wi.z <= 0.0f) continue;
    float3 dir = to_world(frame, wi);
    if (dot(dir, ng) <= 0.0f) continue;
    float r;
    sum += brdf_specular_weight(in, wo, wi) *
           bounce_radiance(SCENE, origin, dir, random01(key, s, 2u), random01(key, s, 3u), random01(key, s, 4u), &r,
                           &rays);
  }
  glossy_out[pixel] = (float4)(finite_or_zero(sum / (float)max(count, 1u)), (float)rays);
}
