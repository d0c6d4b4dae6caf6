// The later bounces of record rays as a queue (the wavefront record trace, GroupSizes::record_trace): the shading of
// a ray's first hit queues the path that must go on from there (first_bounce_from_hit's PATH_CONTINUES or
// PATH_STEPS_THEN_GATHERS); one launch a bounce then takes every queued path one path_bounce further, and a last one
// adds what each gathered to its sample. No kernel holds a path's loop, and each queued path makes exactly the float
// operations radiance_from_hit makes in its loop, so the samples are the same bits as one kernel's. A path's slot comes
// from an atomic counter: its order in the queue changes nothing a path computes, only where it is kept.
#ifndef RCSPLAT_PATH_QUEUE_H
#define RCSPLAT_PATH_QUEUE_H
#include "bounce.h"

// Queues a path from the hit `hit` reached along dir; sample: where its (first-hit light, distance) waits in the
// samples buffer, launch_sample its place in the launch.
inline void queue_path(__global QueuedPath* paths, volatile __global uint* path_count, uint sample, uint launch_sample,
                       PathContinuation more, uint mode, HitDesc hit, float3 dir, float weight, uint rays) {
  __global QueuedPath* path = paths + atomic_inc(path_count);
  path->sample = sample;
  path->launch_sample = launch_sample;
  path->key = more.key;
  path->stream_sample = more.sample;
  path->mode = mode;
  path->rays = rays;
  path->prim = hit.prim;
  path->u = hit.u;
  path->v = hit.v;
  vstore3(dir, 0, path->dir);
  vstore3((float3)(1.0f), 0, path->throughput);
  vstore3((float3)(0.0f), 0, path->sum);
  path->weight = weight;
}

// Bounce k of a queued path (k = 0 for every path first; a path that ended is left as it is).
inline void step_queued_path(SCENE_ARGS GATHER_MAP_ARGS, __global QueuedPath* path, uint k, uint bounces) {
  const uint mode = path->mode;
  if (mode == PATH_ENDED) return;
  PathContinuation more = {path->key, path->stream_sample, bounces};
  float3 dir = vload3(0, path->dir), throughput = vload3(0, path->throughput), sum = vload3(0, path->sum);
  HitSurface h = hit_surface(triangles, path->prim, path->u, path->v, dir);
  uint rays = path->rays;
  bool goes_on = path_bounce(SCENE GATHER_MAP, &h, &dir, &throughput, more, k, mode, &sum, &rays);
  vstore3(sum, 0, path->sum);
  path->rays = rays;
  if (!goes_on || k + 1u == bounces) {
    path->mode = PATH_ENDED;
    return;
  }
  // The surface it now stands on, as the trace gave it: hit_surface builds it again for the next bounce.
  path->prim = h.hit.prim;
  path->u = h.hit.u;
  path->v = h.hit.v;
  vstore3(dir, 0, path->dir);
  vstore3(throughput, 0, path->throughput);
}

#endif
