// Light from outside the scene (HAS_ENVIRONMENT): a uniform sky (a 1 x 1 map) or an equirectangular map, rotated about
// +Y. The map is piecewise constant per texel; its rows run from +Y (theta = 0) down, its columns from -Z round
// through +X (Mitsuba's convention: u = (1 + atan2(x, -z) / pi) / 2, v = acos(y) / pi).
//
// Each texel is split in two (host/scene/environment.h): the smooth part (radiance up to a few times the map's mean)
// is found by rays that leave the scene, the cache's hemisphere rays and BRDF samples above all, which see it for free
// and average it smoothly; the peak (a sun) is sampled by shadow rays in proportion to its luminance, as emitters
// are. Every direction's radiance is counted once: smooth where a gathering ray escapes, peak by light sampling.
// Texel w holds the smooth fraction of its RGB.
#ifndef RCSPLAT_ENVIRONMENT_H
#define RCSPLAT_ENVIRONMENT_H
#include "counter_random.h"
#include "lighting.h"
#include "scene_args.h"

#if HAS_ENVIRONMENT
// The map's direction for a world direction (the map is rotated about +Y by the environment's angle).
inline float3 environment_from_world(SceneCounts c, float3 d) {
  float cs = c.environment_rotation[0], sn = c.environment_rotation[1];
  return (float3)(cs * d.x - sn * d.z, d.y, sn * d.x + cs * d.z);
}
inline float3 world_from_environment(SceneCounts c, float3 d) {
  float cs = c.environment_rotation[0], sn = c.environment_rotation[1];
  return (float3)(cs * d.x + sn * d.z, d.y, -sn * d.x + cs * d.z);
}

// The texel a world direction looks up.
inline uint environment_texel(SceneCounts c, float3 world_dir) {
  float3 d = environment_from_world(c, world_dir);
  float u = 0.5f * (1.0f + atan2(d.x, -d.z) * RC_INV_PI);
  float v = acos(clamp(d.y, -1.0f, 1.0f)) * RC_INV_PI;
  uint w = c.environment_width, h = c.environment_height;
  uint i = min((uint)(u * (float)w), w - 1u), j = min((uint)(v * (float)h), h - 1u);
  return j * w + i;
}

// Compiled in (HAS_ENVIRONMENT) and present: tests compile the code for scenes without one, which must see black.
inline bool environment_present(SceneCounts c) { return c.environment_width > 0u; }

// Everything the environment sends along -world_dir: what camera rays that leave the scene see.
inline float3 environment_radiance(__global const float4* environment, SceneCounts c, float3 world_dir) {
  if (!environment_present(c)) return (float3)(0.0f);
  return environment[environment_texel(c, world_dir)].xyz;
}

// The part gathering rays find when they leave the scene (hemisphere rays, BRDF samples, path continuations).
inline float3 environment_smooth(__global const float4* environment, SceneCounts c, float3 world_dir) {
  if (!environment_present(c)) return (float3)(0.0f);
  float4 t = environment[environment_texel(c, world_dir)];
  return t.xyz * t.w;
}

// The peak's part of a texel (its luminance is what the peak's sampling density is proportional to).
inline float3 environment_peak_of(float4 t) { return t.xyz * (1.0f - t.w); }

// A direction toward the peak from uniform (u1, u2): a row by the marginal CDF, a texel by the row's CDF (both of
// luminance times solid angle), then uniformly in solid angle inside the texel (uniform in phi and in cos theta), so
// the density per solid angle is exactly luminance / environment_peak_power. Returns the peak radiance divided by
// that density, *pdf the density (0: no sample). With ENVIRONMENT_UNIFORM_SAMPLING (tests) the direction is uniform
// on the sphere instead, the same integral by a different estimator.
inline float3 environment_peak_sample(__global const float4* environment, __global const float* cdf, SceneCounts c,
                                      float u1, float u2, float3* dir, float* pdf) {
  *pdf = 0.0f;
  *dir = (float3)(0.0f, 1.0f, 0.0f);
  if (!(c.environment_peak_power > 0.0f)) return (float3)(0.0f);
#if ENVIRONMENT_UNIFORM_SAMPLING
  float z = 1.0f - 2.0f * u1, r = sqrt(max(0.0f, 1.0f - z * z)), phi = 2.0f * RC_PI * u2;
  *dir = (float3)(r * cos(phi), z, r * sin(phi));
  *pdf = 0.25f * RC_INV_PI;
  return environment_peak_of(environment[environment_texel(c, *dir)]) * (4.0f * RC_PI);
#else
  uint w = c.environment_width, h = c.environment_height;
  __global const float* marginal = cdf;
  uint j = cdf_bin(marginal + 1, h, u1);  // the CDFs start with their 0
  float row_width = marginal[j + 1u] - marginal[j];
  if (!(row_width > 0.0f)) return (float3)(0.0f);
  float v_in = clamp((u1 - marginal[j]) / row_width, 0.0f, 1.0f);
  __global const float* row = cdf + (h + 1u) + j * (w + 1u);
  uint i = cdf_bin(row + 1, w, u2);
  float texel_width = row[i + 1u] - row[i];
  if (!(texel_width > 0.0f)) return (float3)(0.0f);
  float u_in = clamp((u2 - row[i]) / texel_width, 0.0f, 1.0f);
  float3 peak = environment_peak_of(environment[j * w + i]);
  float lum = luminance(peak);
  if (!(lum > 0.0f)) return (float3)(0.0f);
  // Uniform in cos(theta) between the row's edges, and in phi across the texel.
  float cos_top = cospi((float)j / (float)h), cos_bottom = cospi((float)(j + 1u) / (float)h);
  float cos_t = mix(cos_top, cos_bottom, v_in), sin_t = sqrt(max(0.0f, 1.0f - cos_t * cos_t));
  float phi = 2.0f * RC_PI * (((float)i + u_in) / (float)w) - RC_PI;
  *dir = world_from_environment(c, (float3)(sin_t * sin(phi), cos_t, -sin_t * cos(phi)));
  *pdf = lum / c.environment_peak_power;
  return peak * (c.environment_peak_power / lum);
#endif
}

// What of the light from the scene's outside reaches origin along *dir: 1 or 0, and through glass its transmittance.
// With HAS_GLASS_CAUSTICS a volume bends the ray (escape_transmittance): *dir becomes the direction whose light
// arrives.
inline float3 escapes(BVH_ARGS, float3 origin, float3* dir, RayTally* rays) {
#if HAS_GLASS_CAUSTICS
  return escape_transmittance(BVH, origin, dir, rays);
#else
  return light_passes(BVH, origin, *dir, INFINITY, rays);
#endif
}

// One shadow-ray estimate of the peak's irradiance at p (normal n, geometric normal ng) from uniform (u1, u2); *wi
// the sample's direction.
inline float3 environment_peak_irradiance(SCENE_ARGS, float3 origin, float3 n, float3 ng, float u1, float u2,
                                          float3* wi, RayTally* rays) {
  float pdf;
  float3 l = environment_peak_sample(environment, environment_cdf, scene_counts, u1, u2, wi, &pdf);
  float cos_x = dot(n, *wi);
  if (!(pdf > 0.0f) || cos_x <= 0.0f || dot(ng, *wi) <= 0.0f) return (float3)(0.0f);
  // A shadow ray toward the peak: a glass volume blocks it under HAS_GLASS_CAUSTICS, the map carrying that light.
  const float3 passes = light_passes(BVH, origin, *wi, INFINITY, rays);
  if (!any_positive(passes)) return (float3)(0.0f);
  return l * cos_x * passes;
}

// The environment's irradiance at a Lambertian point that a gathering ray found (its direct light): the smooth part
// by one cosine-weighted ray that must escape, the peak by one light sample. (u1 .. u4) uniform.
inline float3 environment_irradiance(SCENE_ARGS, float3 p, float3 n, float3 ng, float u1, float u2, float u3,
                                     float u4, RayTally* rays) {
  if (!environment_present(scene_counts)) return (float3)(0.0f);
  float3 origin = offset_ray_origin(p, ng);
  float3 t, b, wi;
  tangent_frame(n, &t, &b);
  float3 dir = cosine_direction(t, b, n, u1, u2);
  float3 e = (float3)(0.0f);
  if (dot(dir, ng) > 0.0f) {
    const float3 passes = escapes(BVH, origin, &dir, rays);
    if (any_positive(passes))
      e += RC_PI * environment_smooth(environment, scene_counts, dir) * passes;  // cosine-weighted: L cos / pdf = pi L
  }
  e += environment_peak_irradiance(SCENE, origin, n, ng, u3, u4, &wi, rays);
  return e;
}

// Two more uniform numbers for the environment, derived from a light sample's (u, v) by hashing, so that the callers
// of hit_direct keep their random dimensions (and a scene without an environment its bits).
inline float2 environment_extra_randoms(float u, float v, uint salt) {
  uint h = hash_u32(as_uint(u) ^ hash_u32(as_uint(v) ^ hash_u32(salt + STREAM_ENVIRONMENT_EXTRA)));
  return (float2)((float)(h >> 8), (float)(hash_u32(h) >> 8)) * (1.0f / 16777216.0f);
}
#endif

#endif
