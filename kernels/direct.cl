// Direct light at each G-buffer point: punctual lights (point, spot, directional) with shadow rays, emissive
// triangles sampled as area lights with stratified samples, and the environment's peak (a sun) with as many stratified
// samples (its smooth part is gathered with the indirect light: kernels/environment.h). Lambertian pixels reflect
// albedo / pi times the irradiance; pixels with a specular lobe (HAS_SPECULAR_BRDF) evaluate the BRDF toward the
// camera per light sample, glossy ones adding a BRDF sample per light sample (kernels/reflected_light.h). Emission
// itself is not included. Writes RGB = reflected direct radiance, A = the number of shadow rays the pixel cast.
#include "counter_random.h"
#include "shading_normal.h"
#include "environment.h"
#include "lighting.h"
#include "pixel_rounds.h"
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
inline float3 direct_specular_pixel(SCENE_ARGS, GBufferSample g, SurfaceLayers layers, float3 wo_world,
                                    uint strata_per_axis, uint key, RayTally* rays) {
  float3 p = vload3(0, g.position), n = gbuffer_shading_normal(g), ng = vload3(0, g.geometric_normal);
  float3 origin = offset_ray_origin(p, ng);
  LazyBrdf brdf = built_brdf(gbuffer_layered_brdf(g, layers, n));
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
    result = direct_specular_pixel(SCENE, g, pixel_layers(gbuffer_layers, pixel), wo, strata_per_axis,
                                   hash_u32(pixel ^ hash_u32(params.seed)), &rays);
    direct_out[pixel] = (float4)(result, (float)rays.cast);
    return;
  }
#endif
  if (g.triangle >= 0) {
    float3 p = vload3(0, g.position), n = gbuffer_shading_normal(g), ng = vload3(0, g.geometric_normal);
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
          sum += emitter_sample(BVH, EMITTERS, emitter_count, uv.x, uv.y, p, origin, n, ng, &wi, &pdf, &rays);
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

#if HAS_EMITTERS || HAS_ENVIRONMENT
// Direct light in rounds (DirectPass with a light budget, in scenes with area lights or an environment peak, the only
// ones that compile it): the
// punctual lights once, and sample s of a sub-pixel's sampled light (an emitter sample and an environment-peak sample)
// at point s * s^2 + sub of its output pixel's nested strata (kernels/pixel_rounds.h), so that a pixel's count, however
// its rounds end, stays stratified across its sub-pixels. The first round writes every sub-pixel: direct_out its
// punctual light; direct_sums its samples' sum (RGB) and count; direct_moments their luminance sum and sum of squares,
// their count and the rays cast. Later rounds add; average_direct_samples makes direct_out what direct_light writes.
inline float3 direct_punctual(SCENE_ARGS, GBufferSample g, SurfaceLayers layers, float3 wo_world, RayTally* rays) {
  const float3 p = vload3(0, g.position), n = gbuffer_shading_normal(g), ng = vload3(0, g.geometric_normal);
  const float3 origin = offset_ray_origin(p, ng);
#if HAS_SPECULAR_BRDF
  if (g.lobe != LOBE_NONE) {
    LazyBrdf brdf = built_brdf(gbuffer_layered_brdf(g, layers, n));
    const ShadingFrame frame = shading_frame(n);
    return finite_or_zero(punctual_reflected(SCENE, &brdf, frame, view_local(frame, wo_world), p, origin, ng, rays));
  }
#endif
  float3 irradiance = (float3)(0.0f);
#if HAS_PUNCTUAL_LIGHTS
  float3 wi;
  for (uint i = 0; i < scene_counts.light_count; ++i)
    irradiance += punctual_irradiance(BVH, lights[i], p, origin, n, ng, &wi, rays);
#endif
  return finite_or_zero(vload3(0, g.albedo) * RC_INV_PI * irradiance);
}

inline float3 direct_sampled(SCENE_ARGS, GBufferSample g, SurfaceLayers layers, float3 wo_world, float2 uv,
                             float2 uv_environment, float u_lobe, RayTally* rays) {
  const float3 p = vload3(0, g.position), n = gbuffer_shading_normal(g), ng = vload3(0, g.geometric_normal);
  const float3 origin = offset_ray_origin(p, ng);
  float3 light = (float3)(0.0f);
#if HAS_SPECULAR_BRDF
  if (g.lobe != LOBE_NONE) {
    LazyBrdf brdf = built_brdf(gbuffer_layered_brdf(g, layers, n));
    const ShadingFrame frame = shading_frame(n);
    const float3 wo = view_local(frame, wo_world);
#if HAS_EMITTERS
    if (scene_counts.emitter_count > 0)
      light += emitters_reflected(SCENE, &brdf, g.lobe, frame, wo, p, origin, ng, uv.x, uv.y, u_lobe, rays);
#endif
#if HAS_ENVIRONMENT
    if (scene_counts.environment_peak_power > 0.0f)
      light += environment_peak_reflected(SCENE, &brdf, frame, wo, origin, ng, uv_environment.x, uv_environment.y,
                                          rays);
#endif
    return finite_or_zero(light);
  }
#endif
  float3 wi;
#if HAS_EMITTERS
  if (scene_counts.emitter_count > 0) {
    float pdf;
    light += emitter_sample(BVH, EMITTERS, scene_counts.emitter_count, uv.x, uv.y, p, origin, n, ng, &wi, &pdf, rays);
  }
#endif
#if HAS_ENVIRONMENT
  if (scene_counts.environment_peak_power > 0.0f)
    light += environment_peak_irradiance(SCENE, origin, n, ng, uv_environment.x, uv_environment.y, &wi, rays);
#endif
  return finite_or_zero(vload3(0, g.albedo) * RC_INV_PI * light);
}

__kernel void direct_light_round(SCENE_ARGS, GBUFFER_ARGS, DirectParams params, __global const uint* pixel_list,
                                 uint item_count, __global float4* direct_out, __global float4* direct_sums,
                                 __global float4* direct_moments) {
  const uint i = get_global_id(0), subs = sub_pixels_per_pixel(camera);
  if (i >= item_count * subs) return;
  const uint o = listed_output_pixel(params.listed, pixel_list, i / subs), sub = i % subs;
  const uint pixel = sub_pixel_of(camera, o, sub);
  const bool first_round = params.first_sample == 0u;
  const GBufferSample g = gbuffer[pixel];
  if (g.triangle < 0) {
    if (first_round) direct_out[pixel] = direct_sums[pixel] = direct_moments[pixel] = (float4)(0.0f);
    return;
  }
#if HAS_SPECULAR_BRDF
  const float3 wo = camera_view_direction(camera, vload3(0, g.position));
#else
  const float3 wo = (float3)(0.0f);  // only a specular lobe reads the view
#endif
  RayTally rays = traced_rays(0u);
  const SurfaceLayers layers = pixel_layers(gbuffer_layers, pixel);
  const float3 punctual = first_round ? direct_punctual(SCENE, g, layers, wo, &rays) : (float3)(0.0f);
  const uint key = hash_u32(pixel ^ hash_u32(params.seed)), environment_key = key ^ ENVIRONMENT_KEY;
  const uint strata_key = hash_u32(o ^ hash_u32(params.seed ^ STREAM_LIGHT_STRATA));
  float3 sum = (float3)(0.0f);
  float sum_y = 0.0f, sum_y2 = 0.0f;
  for (uint s = params.first_sample; s < params.first_sample + params.round_samples; ++s) {
    const uint t = s * subs + sub;
    const float2 uv = nested_stratum_point(t, strata_key, random01(key, s, 0u), random01(key, s, 1u));
    const float2 uv_environment = nested_stratum_point(t, strata_key ^ ENVIRONMENT_KEY, random01(environment_key, s, 0u),
                                                       random01(environment_key, s, 1u));
    const float3 y = direct_sampled(SCENE, g, layers, wo, uv, uv_environment, random01(key, s, 2u), &rays);
    sum += y;
    const float y_luminance = luminance(y);
    sum_y += y_luminance;
    sum_y2 += y_luminance * y_luminance;
  }
  float4 sums = (float4)(sum, (float)params.round_samples);
  float4 moments = (float4)(sum_y, sum_y2, (float)params.round_samples, (float)rays.cast);
  if (first_round) {
    direct_out[pixel] = (float4)(punctual, 0.0f);
  } else {
    sums += direct_sums[pixel];
    moments += direct_moments[pixel];
  }
  direct_sums[pixel] = sums;
  direct_moments[pixel] = moments;
}

// After the first round: each output pixel's error estimate (host/passes/sample_rounds.h): (the variance of its sampled
// light's luminance, its sub-pixels' samples pooled; the luminance of its punctual and emitted light; the sub-pixels
// pooled; the luminance of its sampled light).
__kernel void direct_pixel_error(GBUFFER_ARGS, __global const float4* direct_out, __global const float4* direct_sums,
                                 __global const float4* direct_moments, uint output_pixels,
                                 __global float4* error_out) {
  const uint o = get_global_id(0);
  if (o >= output_pixels) return;
  const uint subs = sub_pixels_per_pixel(camera);
  PooledMoments pool = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  float other = 0.0f, sampled = 0.0f;
  for (uint sub = 0; sub < subs; ++sub) {
    const uint pixel = sub_pixel_of(camera, o, sub);
    const GBufferSample g = gbuffer[pixel];
    const float4 sums = direct_sums[pixel], moments = direct_moments[pixel];
    other += luminance(finite_or_zero(vload3(0, g.emission) + direct_out[pixel].xyz));
    if (sums.w > 0.0f) sampled += luminance(sums.xyz / sums.w);
    if (g.triangle >= 0 && moments.z >= 1.0f) pool_sub_pixel(&pool, moments, moments.z);
  }
  error_out[o] = pixel_error_estimate(pool, subs, other, sampled);
}

// Each sub-pixel's direct light as direct_light writes it: punctual plus the mean of its samples (RGB), rays (A).
__kernel void average_direct_samples(__global const float4* direct_sums, __global const float4* direct_moments,
                                     uint pixel_count, __global float4* direct_out) {
  const uint i = get_global_id(0);
  if (i >= pixel_count) return;
  const float4 sums = direct_sums[i];
  direct_out[i] = (float4)(direct_out[i].xyz + (sums.w > 0.0f ? sums.xyz / sums.w : (float3)(0.0f)),
                           direct_moments[i].w);
}
#endif
