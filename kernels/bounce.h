// One indirect bounce: what a ray leaving a surface sees, counted as the directly lit radiance reflected by the surface it
// lands on (never that surface's emission, which direct light already counts: ALGORITHM.md section 1).
// Shared by the record pass and the path tracer so that both estimate the same integral.
#ifndef RCSPLAT_BOUNCE_H
#define RCSPLAT_BOUNCE_H
#include "lighting.h"
#include "scene_args.h"
#include "surface.h"
#if HAS_SPECULAR_BRDF
#include "reflected_light.h"
#endif

// Radiance arriving at origin from direction dir after one reflection; (u, v) pick the light sample at the hit, and
// u_lobe the lobe of its BRDF sample where the hit is glossy. *distance is the hit distance, INFINITY on a miss.
inline float3 bounce_radiance(SCENE_ARGS, float3 origin, float3 dir, float u, float v, float u_lobe, float* distance,
                              uint* rays) {
  RayPrecomp r = ray_precompute(origin, dir);
  TraceHit hit;
  ++*rays;
  if (!bvh_trace(BVH, &r, 0.0f, INFINITY, false, &hit)) {
    *distance = INFINITY;
    return (float3)(0.0f);
  }
  *distance = hit.t;
  SurfacePoint s = surface_at(triangles, hit.prim, hit.u, hit.v);
  bool back = dot(s.geometric_normal, dir) > 0.0f;  // surfaces reflect on both sides, as in the G-buffer
  float3 ng = back ? -s.geometric_normal : s.geometric_normal;
  float3 ns = back ? -s.shading_normal : s.shading_normal;
  if (dot(ns, ng) <= 0.0f) ns = ng;
  float3 albedo = surface_albedo(materials, textures, texels, &s);
#if HAS_SPECULAR_BRDF
  SurfaceLobe lobe = surface_lobe(materials, textures, texels, &s);
  if (lobe.lobe != LOBE_NONE)
    return direct_reflected(SCENE, surface_brdf(albedo, lobe), lobe.lobe, s.position, ns, ng, -dir, u, v, u_lobe, rays);
#endif
  float3 e = direct_irradiance(BVH, lights, scene_counts.light_count, emitters, scene_counts.emitter_count,
                               s.position, ns, ng, u, v, rays);
  return finite_or_zero(albedo * RC_INV_PI * e);
}

#endif
