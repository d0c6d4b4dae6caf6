// One indirect bounce: what a ray leaving a surface sees, counted as the directly lit radiance reflected by the surface it
// lands on (never that surface's emission, which direct light already counts: ALGORITHM.md section 1).
// Shared by the record pass and the path tracer so that both estimate the same integral.
#ifndef RCSPLAT_BOUNCE_H
#define RCSPLAT_BOUNCE_H
#include "lighting.h"
#include "scene_args.h"
#include "surface.h"

// Radiance arriving at origin from direction dir after one reflection; (u, v) pick the light sample at the hit.
// *distance is the hit distance, INFINITY on a miss.
inline float3 bounce_radiance(SCENE_ARGS, float3 origin, float3 dir, float u, float v, float* distance,
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
  float3 e = direct_irradiance(BVH, lights, scene_counts.light_count, emitters, scene_counts.emitter_count,
                               s.position, ns, ng, u, v, rays);
  return finite_or_zero(albedo * RC_INV_PI * e);
}

// An orthonormal frame around the unit vector n (Duff et al. 2017, branch-free).
inline void tangent_frame(float3 n, float3* t, float3* b) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  *t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = (float3)(c, sign + n.y * n.y * a, -n.y);
}

#endif
