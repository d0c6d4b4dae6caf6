// Casts a batch of arbitrary rays: closest hits or occlusion. Used by the tests (against Embree) and the benchmarks.
#include "scene_args.h"
#include "traverse.h"

inline RayPrecomp load_ray(RayDesc ray) { return ray_precompute(vload3(0, ray.origin), vload3(0, ray.direction)); }

__kernel void cast_closest(SCENE_ARGS, __global const RayDesc* rays, RayCastParams params, __global HitDesc* hits) {
  uint i = get_global_id(0);
  if (i >= params.ray_count) return;
  RayDesc ray = rays[i];
  RayPrecomp r = load_ray(ray);
  TraceHit h;
  bvh_trace(BVH, &r, ray.tmin, ray.tmax, false, &h);
  HitDesc out;
  out.t = h.t;
  out.u = h.prim >= 0 ? h.u : 0.0f;
  out.v = h.prim >= 0 ? h.v : 0.0f;
  out.prim = h.prim;
  hits[i] = out;
}

__kernel void cast_occlusion(SCENE_ARGS, __global const RayDesc* rays, RayCastParams params, __global int* occluded) {
  uint i = get_global_id(0);
  if (i >= params.ray_count) return;
  RayDesc ray = rays[i];
  RayPrecomp r = load_ray(ray);
  TraceHit h;
  occluded[i] = bvh_trace(BVH, &r, ray.tmin, ray.tmax, true, &h) ? 1 : 0;
}
