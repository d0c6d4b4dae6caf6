// Direct light reflected toward a viewer by the full BRDF (kernels/brdf.h), for surfaces with a specular lobe; compiled
// only for scenes that have one (HAS_SPECULAR_BRDF). Punctual lights count through their delta. Emissive triangles:
// a rough lobe takes one light sample; a glossy lobe adds one BRDF sample and weighs the two by the power heuristic
// (Veach 1997), so that a sharp lobe's reflection of an area light converges as fast as a wide lobe's.
#ifndef RCSPLAT_REFLECTED_LIGHT_H
#define RCSPLAT_REFLECTED_LIGHT_H
#include "brdf_frame.h"
#include "caustic_map.h"
#include "environment.h"
#include "lighting.h"
#include "scene_args.h"
#include "surface.h"

// The BRDF of a surface of this base colour and lobe, whose shading normal is n (the local frame's +z).
inline BrdfInputs surface_brdf(float3 base_color, SurfaceLobe lobe, float3 n) {
#if HAS_LAYERS
  return with_layers(brdf_inputs(base_color, lobe.metallic, lobe.roughness, lobe.specular), lobe.layers, n);
#else
  return brdf_inputs(base_color, lobe.metallic, lobe.roughness, lobe.specular);
#endif
}

// The BRDF of a surface, built where a light sample first needs it (lazy_brdf_inputs): from the G-buffer's stored
// inputs (built), or from a ray's hit, whose textures are then read once (hit_albedo, hit_lobe). Each use below
// sits where the eager code evaluated the BRDF, so the results are the same bits.
typedef struct {
  BrdfInputs in;
  int built;
  HitSurface* hit;  // what to build it from while !built
} LazyBrdf;

inline LazyBrdf built_brdf(BrdfInputs in) {
  LazyBrdf b;
  b.in = in;
  b.built = 1;
  b.hit = 0;
  return b;
}

inline LazyBrdf lazy_hit_brdf(HitSurface* hit) {
  LazyBrdf b;
  b.built = 0;
  b.hit = hit;
  return b;
}

inline BrdfInputs lazy_brdf_inputs(__global const Material* materials, __global const TextureInfo* textures,
                                   __global const uint* texels, LazyBrdf* b) {
  if (!b->built) {
    b->in = surface_brdf(hit_albedo(materials, textures, texels, b->hit),
                         hit_lobe(materials, textures, texels, b->hit), b->hit->ns);
    b->built = 1;
  }
  return b->in;
}
#define BRDF_IN lazy_brdf_inputs(materials, textures, texels, brdf)

// The power heuristic's weight for a sample of the technique with density a against one with density b.
inline float power_heuristic(float a, float b) {
  float a2 = a * a, b2 = b * b;
  return a2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

#if HAS_EMITTERS
// What a ray from origin along the unit dir finds first, if that is the emitting side of an emissive triangle: its
// radiance, and in *light_pdf the density (per solid angle) with which emitter_sample would have chosen that direction.
inline float3 emitter_hit(SCENE_ARGS, float3 origin, float3 dir, float* light_pdf, RayTally* rays) {
  *light_pdf = 0.0f;
  TraceHit hit;
  if (!closest_hit(BVH, rays, origin, dir, &hit)) return (float3)(0.0f);
#if HAS_TRANSMISSION
  // Through glass: the emitter the chain reaches, at the chain's length (exact for thin-walled glass). With
  // HAS_GLASS_CAUSTICS, an emitter seen through a volume is the glass caustic map's light, as for light samples.
  float distance;
  bool met_volume;
  const float3 passes = pass_glass_noting_volumes(BVH, rays, &hit, &dir, &distance, &met_volume);
  if (hit.prim < 0) return (float3)(0.0f);
#if HAS_GLASS_CAUSTICS
  if (met_volume) return (float3)(0.0f);
#endif
  hit.t = distance;
#else
  const float3 passes = (float3)(1.0f);
#endif
  int index = triangles[hit.prim].emitter;
  if (index < 0) return (float3)(0.0f);
  EmissiveTriangle e = emitters[index];
  float cos_y = -dot(vload3(0, triangles[hit.prim].geometric_normal), dir);
  if (emitter_double_sided(e)) cos_y = fabs(cos_y);
  if (!(cos_y > 0.0f)) return (float3)(0.0f);
  *light_pdf = emitter_solid_angle_pdf(e, hit.t * hit.t, cos_y);
  return emitter_radiance_at(e, hit.u, hit.v, triangles, materials, textures, texels) * passes;  // e: hit.prim's
}
#endif

// Punctual lights' radiance reflected toward wo (world, unit) at p.
inline float3 punctual_reflected(SCENE_ARGS, LazyBrdf* brdf, ShadingFrame frame, float3 wo_local, float3 p,
                                 float3 origin, float3 ng, RayTally* rays) {
  float3 sum = (float3)(0.0f);
#if HAS_PUNCTUAL_LIGHTS
  for (uint i = 0; i < scene_counts.light_count; ++i) {
    float3 wi;
    float3 e = punctual_irradiance(BVH, lights[i], p, origin, frame.n, ng, &wi, rays);
    if (any_positive(e)) sum += brdf_eval(BRDF_IN, wo_local, to_local(frame, wi)) * e;
  }
#endif
  return sum;
}

// Glossy lobes (sampled or radiance-cached) pair each light sample with a BRDF sample; rough ones take light samples.
inline bool lobe_takes_brdf_samples(int lobe) { return lobe == LOBE_GLOSSY || lobe == LOBE_HSH; }

// One estimate of the emitters' radiance reflected toward wo: a light sample at (u, v), and for a glossy lobe also a
// BRDF sample at (u_lobe, u, v), the two weighed by multiple importance sampling. Reusing (u, v) keeps each technique
// unbiased on its own, and the weights sum to one at every direction, so their sum is too.
inline float3 emitters_reflected(SCENE_ARGS, LazyBrdf* brdf, int lobe, ShadingFrame frame, float3 wo_local, float3 p,
                                 float3 origin, float3 ng, float u, float v, float u_lobe, RayTally* rays) {
  float3 sum = (float3)(0.0f);
#if HAS_EMITTERS
  if (scene_counts.emitter_count == 0) return sum;
  float3 wi;
  float light_pdf;
  float3 e = emitter_sample(BVH, EMITTERS, scene_counts.emitter_count, u, v, p, origin, frame.n, ng, &wi, &light_pdf,
                            rays);
  if (light_pdf > 0.0f) {
    float3 wi_local = to_local(frame, wi);
    float weight =
        lobe_takes_brdf_samples(lobe) ? power_heuristic(light_pdf, brdf_pdf(BRDF_IN, wo_local, wi_local)) : 1.0f;
    sum += brdf_eval(BRDF_IN, wo_local, wi_local) * e * weight;
  }
  if (lobe_takes_brdf_samples(lobe)) {
    float3 wi_local;
    float brdf_pdf_value;
    float3 throughput = brdf_sample(BRDF_IN, wo_local, u_lobe, u, v, &wi_local, &brdf_pdf_value);
    float3 dir = to_world(frame, wi_local);
    if (brdf_pdf_value > 0.0f && dot(dir, ng) > 0.0f) {
      float pdf_of_light;
      float3 radiance = emitter_hit(SCENE, origin, dir, &pdf_of_light, rays);
      sum += throughput * radiance * power_heuristic(brdf_pdf_value, pdf_of_light);
    }
  }
#endif
  return finite_or_zero(sum);
}

#if HAS_ENVIRONMENT
// One light-sample estimate of the environment's peak reflected toward wo: the smooth part is left to the rays that
// gather (kernels/environment.h).
inline float3 environment_peak_reflected(SCENE_ARGS, LazyBrdf* brdf, ShadingFrame frame, float3 wo_local,
                                         float3 origin, float3 ng, float u1, float u2, RayTally* rays) {
  float3 wi;
  float3 e = environment_peak_irradiance(SCENE, origin, frame.n, ng, u1, u2, &wi, rays);
  if (!any_positive(e)) return (float3)(0.0f);
  return brdf_eval(BRDF_IN, wo_local, to_local(frame, wi)) * e;
}

// The environment reflected toward wo by a surface a gathering ray found: the peak by a light sample, the smooth part
// by a BRDF sample that must escape. Its random numbers come from the light sample's (u, v).
inline float3 environment_reflected(SCENE_ARGS, LazyBrdf* brdf, ShadingFrame frame, float3 wo_local, float3 origin,
                                    float3 ng, float u, float v, RayTally* rays) {
  if (!environment_present(scene_counts)) return (float3)(0.0f);
  float2 peak_u = environment_extra_randoms(u, v, 0u), lobe_u = environment_extra_randoms(u, v, 1u);
  float3 sum = environment_peak_reflected(SCENE, brdf, frame, wo_local, origin, ng, peak_u.x, peak_u.y, rays);
  float3 wi_local;
  float pdf;
  float3 throughput = brdf_sample(BRDF_IN, wo_local, environment_extra_randoms(u, v, 2u).x, lobe_u.x, lobe_u.y, &wi_local,
                                  &pdf);
  float3 dir = to_world(frame, wi_local);
  if (pdf > 0.0f && dot(dir, ng) > 0.0f) {
    const float3 passes = escapes(BVH, origin, &dir, rays);
    if (any_positive(passes)) sum += throughput * environment_smooth(environment, scene_counts, dir) * passes;
  }
  return sum;
}
#endif

// Direct light reflected toward wo_world (unit, pointing away from p) by a surface with a specular lobe: every
// punctual light, one emitter estimate and, where there is one, one estimate of the environment.
inline float3 direct_reflected(SCENE_ARGS, LazyBrdf* brdf, int lobe, float3 p, float3 n, float3 ng, float3 wo_world,
                               float u, float v, float u_lobe, RayTally* rays) {
  ShadingFrame frame = shading_frame(n);
  float3 wo_local = view_local(frame, wo_world);
  float3 origin = offset_ray_origin(p, ng);
  float3 l = punctual_reflected(SCENE, brdf, frame, wo_local, p, origin, ng, rays) +
             emitters_reflected(SCENE, brdf, lobe, frame, wo_local, p, origin, ng, u, v, u_lobe, rays);
#if HAS_ENVIRONMENT
  l += environment_reflected(SCENE, brdf, frame, wo_local, origin, ng, u, v, rays);
#endif
#if HAS_GLASS_CAUSTICS
  // The light glass volumes passed, as irradiance: a sharp lobe's highlight of it is not simulated.
  l += irradiance_reflected(BRDF_IN, lobe, wo_local, caustic_levels_irradiance(GLASS_CAUSTIC_MAP, p, ng, 0.0f));
#endif
  return finite_or_zero(l);
}

#endif
