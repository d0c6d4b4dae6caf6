// Traces the rays that wavefront shading queued (kernels/ray_queue.h) and writes each answer into its slot: the
// closest hit, or for a shadow ray whether anything blocks it. The queue's length stays on the device: work-items past
// it return at once.
#include "ray_queue.h"
#include "scene_args.h"

__kernel void trace_queued_rays(SCENE_ARGS, __global const QueuedRay* queue, __global const uint* queue_length,
                                __global HitDesc* answers) {
  const uint i = get_global_id(0);
  if (i >= *queue_length) return;
  const QueuedRay ray = queue[i];
  const bool closest = (ray.slot & QUEUED_RAY_CLOSEST) != 0u;
  RayPrecomp r = ray_precompute(vload3(0, ray.origin), vload3(0, ray.direction));
  TraceHit h = {INFINITY, 0.0f, 0.0f, -1};
  const bool hit = bvh_trace(BVH, &r, 0.0f, ray.tmax, !closest, &h);
  HitDesc answer = {h.t, h.u, h.v, hit ? (closest ? h.prim : 0) : -1};
  answers[ray.slot & ~QUEUED_RAY_CLOSEST] = answer;
}
