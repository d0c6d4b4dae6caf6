// Direct light at each G-buffer point: punctual lights (point, spot, directional) with shadow rays, emissive
// triangles sampled as area lights with stratified samples, and the environment's peak (a sun) with as many stratified
// samples (its smooth part is gathered with the indirect light: kernels/environment.h). Lambertian pixels reflect
// albedo / pi times the irradiance; pixels with a specular lobe (HAS_SPECULAR_BRDF) evaluate the BRDF toward the
// camera per light sample, glossy ones adding a BRDF sample per light sample (kernels/reflected_light.h). Emission
// itself is not included. Writes RGB = reflected direct radiance, A = the number of shadow rays the pixel cast.
#include "counter_random.h"
#include "environment.h"
#include "lighting.h"
#include "scene_args.h"
#if HAS_SPECULAR_BRDF
#include "reflected_light.h"
#endif

// The light sample of stratum (i, j) of a strata x strata grid over the emitters' unit square, sample s = j * strata + i.
inline float2 light_stratum_sample(uint key, uint i, uint j, uint strata) {
  uint s = j * strata + i;
  float inv = 1.0f / (float)strata;
  return (float2)(((float)i + random01(key, s, 0u)) * inv, ((float)j + random01(key, s, 1u)) * inv);
}

// The environment's samples draw from their own stream, independent of the emitters'.
#define ENVIRONMENT_KEY STREAM_ENVIRONMENT_SHADOW

#if HAS_SPECULAR_BRDF
// Direct light reflected toward the camera by a pixel with a specular lobe: every punctual light, and the emitters
// with the same stratified light samples as a Lambertian pixel, each paired with a BRDF sample where the lobe is
// glossy.
inline float3 direct_specular_pixel(SCENE_ARGS, GBufferSample g, float3 wo_world, uint strata_per_axis, uint key,
                                    RayTally* rays) {
  float3 p = vload3(0, g.position), n = vload3(0, g.normal), ng = vload3(0, g.geometric_normal);
  float3 origin = offset_ray_origin(p, ng);
  LazyBrdf brdf = built_brdf(gbuffer_brdf(g));
  ShadingFrame frame = shading_frame(n);
  float3 wo = view_local(frame, wo_world);
  float3 result = punctual_reflected(SCENE, &brdf, frame, wo, p, origin, ng, rays);
#if HAS_EMITTERS
  if (scene_counts.emitter_count > 0 && strata_per_axis > 0) {
    float3 sum = (float3)(0.0f);
    float inv = 1.0f / (float)strata_per_axis;
    for (uint j = 0; j < strata_per_axis; ++j) {
      for (uint i = 0; i < strata_per_axis; ++i) {
        float2 uv = light_stratum_sample(key, i, j, strata_per_axis);
        sum += emitters_reflected(SCENE, &brdf, g.lobe, frame, wo, p, origin, ng, uv.x, uv.y,
                                  random01(key, j * strata_per_axis + i, 2u), rays);
      }
    }
    result += sum * (inv * inv);
  }
#endif
#if HAS_ENVIRONMENT
  if (scene_counts.environment_peak_power > 0.0f && strata_per_axis > 0) {
    float3 sum = (float3)(0.0f);
    float inv = 1.0f / (float)strata_per_axis;
    for (uint j = 0; j < strata_per_axis; ++j) {
      for (uint i = 0; i < strata_per_axis; ++i) {
        float2 uv = light_stratum_sample(key ^ ENVIRONMENT_KEY, i, j, strata_per_axis);
        sum += environment_peak_reflected(SCENE, &brdf, frame, wo, origin, ng, uv.x, uv.y, rays);
      }
    }
    result += sum * (inv * inv);
  }
#endif
  return finite_or_zero(result);
}
#endif

__kernel void direct_light(SCENE_ARGS, GBUFFER_ARGS, DirectParams params, __global float4* direct_out) {
  uint pixel = get_global_id(0);
  if (pixel >= (uint)(camera->width * camera->height)) return;
  const uint light_count = scene_counts.light_count, emitter_count = scene_counts.emitter_count;
  const uint strata_per_axis = params.strata_per_axis;
  GBufferSample g = gbuffer[pixel];
  float3 result = (float3)(0.0f);
  RayTally rays = traced_rays(0u);
#if HAS_SPECULAR_BRDF
  if (g.triangle >= 0 && g.lobe != LOBE_NONE) {
    float3 wo = camera_view_direction(camera, vload3(0, g.position));
    result = direct_specular_pixel(SCENE, g, wo, strata_per_axis, hash_u32(pixel ^ hash_u32(params.seed)), &rays);
    direct_out[pixel] = (float4)(result, (float)rays.cast);
    return;
  }
#endif
  if (g.triangle >= 0) {
    float3 p = vload3(0, g.position), n = vload3(0, g.normal), ng = vload3(0, g.geometric_normal);
    float3 origin = offset_ray_origin(p, ng);
    float3 irradiance = (float3)(0.0f);
#if HAS_PUNCTUAL_LIGHTS
    float3 wi;
    for (uint i = 0; i < light_count; ++i) irradiance += punctual_irradiance(BVH, lights[i], p, origin, n, ng, &wi, &rays);
#endif
#if HAS_EMITTERS
    if (emitter_count > 0 && strata_per_axis > 0) {
      float3 sum = (float3)(0.0f);
      float inv = 1.0f / (float)strata_per_axis;
      uint key = hash_u32(pixel ^ hash_u32(params.seed));
      for (uint j = 0; j < strata_per_axis; ++j) {
        for (uint i = 0; i < strata_per_axis; ++i) {
          float2 uv = light_stratum_sample(key, i, j, strata_per_axis);
          float3 wi;
          float pdf;
          sum += emitter_sample(BVH, emitters, emitter_count, uv.x, uv.y, p, origin, n, ng, &wi, &pdf, &rays);
        }
      }
      irradiance += sum * (inv * inv);
    }
#endif
#if HAS_ENVIRONMENT
    if (scene_counts.environment_peak_power > 0.0f && strata_per_axis > 0) {
      float3 sum = (float3)(0.0f), wi;
      float inv = 1.0f / (float)strata_per_axis;
      uint key = hash_u32(pixel ^ hash_u32(params.seed)) ^ ENVIRONMENT_KEY;
      for (uint j = 0; j < strata_per_axis; ++j) {
        for (uint i = 0; i < strata_per_axis; ++i) {
          float2 uv = light_stratum_sample(key, i, j, strata_per_axis);
          sum += environment_peak_irradiance(SCENE, origin, n, ng, uv.x, uv.y, &wi, &rays);
        }
      }
      irradiance += sum * (inv * inv);
    }
#endif
    result = finite_or_zero(vload3(0, g.albedo) * RC_INV_PI * irradiance);
  }
  direct_out[pixel] = (float4)(result, (float)rays.cast);  // w: shadow rays cast (exact below 2^24)
}
