// Direct light at each G-buffer point: punctual lights (point, spot, directional) with shadow rays, and emissive
// triangles sampled as area lights with stratified samples. Lambertian reflection; emission itself is not included.
// Writes RGB = reflected direct radiance, A = the number of shadow rays the pixel cast.
#include "lighting.h"
#include "scene_args.h"

__kernel void direct_light(SCENE_ARGS, GBUFFER_ARGS, DirectParams params, __global float4* direct_out) {
  uint pixel = get_global_id(0);
  if (pixel >= (uint)(camera->width * camera->height)) return;
  const uint light_count = scene_counts.light_count, emitter_count = scene_counts.emitter_count;
  const uint strata_per_axis = params.strata_per_axis;
  GBufferSample g = gbuffer[pixel];
  float3 result = (float3)(0.0f);
  uint rays = 0;
  if (g.triangle >= 0) {
    float3 p = vload3(0, g.position), n = vload3(0, g.normal), ng = vload3(0, g.geometric_normal);
    float3 origin = offset_ray_origin(p, ng);
    float3 irradiance = (float3)(0.0f);
#if HAS_PUNCTUAL_LIGHTS
    for (uint i = 0; i < light_count; ++i) irradiance += punctual_irradiance(BVH, lights[i], p, origin, n, ng, &rays);
#endif
#if HAS_EMITTERS
    if (emitter_count > 0 && strata_per_axis > 0) {
      float3 sum = (float3)(0.0f);
      float inv = 1.0f / (float)strata_per_axis;
      uint key = hash_u32(pixel ^ hash_u32(params.seed));
      for (uint j = 0; j < strata_per_axis; ++j) {
        for (uint i = 0; i < strata_per_axis; ++i) {
          uint s = j * strata_per_axis + i;
          float u = ((float)i + random01(key, s, 0u)) * inv;
          float v = ((float)j + random01(key, s, 1u)) * inv;
          sum += emitter_sample(BVH, emitters, emitter_count, u, v, p, origin, n, ng, &rays);
        }
      }
      irradiance += sum * (inv * inv);
    }
#endif
    result = finite_or_zero(vload3(0, g.albedo) * RC_INV_PI * irradiance);
  }
  direct_out[pixel] = (float4)(result, (float)rays);  // w: shadow rays cast (exact below 2^24)
}
