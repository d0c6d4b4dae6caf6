// The bounces after a ray's first hit as a queue (the wavefront trace, GroupSizes::record_trace): the shading of the
// first hit queues the path that must go on from there; one launch a bounce then takes every queued path one bounce
// further, and a last one adds what each gathered to its sample. No kernel holds a path's loop, and each queued path
// makes exactly the float operations the one-kernel trace makes in its loop, so the samples are the same bits. A path's
// slot comes from an atomic counter: its order in the queue changes nothing a path computes, only where it is kept.
// The record pass (kernels/records.cl) and the glossy pass (kernels/glossy.cl) queue their paths so; each steps them
// with its own bounce (path_bounce, glossy_path_bounce) between load_queued_path and store_queued_path.
#ifndef RCSPLAT_PATH_QUEUE_H
#define RCSPLAT_PATH_QUEUE_H
#include "bounce.h"

// Set on a queued path's mode once it stops.
#define PATH_ENDED 0x100u
// A glossy sample's path that reads the records where they reach (kernels/glossy.cl): its sum starts at the first
// hit's light and is its whole light.
#define PATH_READS_RECORDS 4u

// Queues a path from the hit `hit` reached along dir, its sum starting at `sum` and its throughput at `throughput` (what
// glass on the way kept: kernels/glass.h); sample: where its first hit's light waits, launch_sample where its rays are
// counted.
inline void queue_path(__global QueuedPath* paths, volatile __global uint* path_count, uint sample, uint launch_sample,
                       PathContinuation more, uint mode, HitDesc hit, float3 dir, float3 sum, float3 throughput,
                       float weight, uint rays) {
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
  vstore3(throughput, 0, path->throughput);
  vstore3(sum, 0, path->sum);
  path->weight = weight;
}

// A queued path's state for its next bounce; false: it has ended.
inline bool load_queued_path(HIT_SURFACE_ARGS, __global const QueuedPath* path,
                             uint later_bounces, HitSurface* h, float3* dir, float3* throughput, float3* sum,
                             PathContinuation* more, uint* rays) {
  if (path->mode & PATH_ENDED) return false;
  more->key = path->key;
  more->sample = path->stream_sample;
  more->bounces = later_bounces;
  *dir = vload3(0, path->dir);
  *throughput = vload3(0, path->throughput);
  *sum = vload3(0, path->sum);
  *h = hit_surface(HIT_SURFACE, path->prim, path->u, path->v, *dir, 0.0f);  // a later bounce: texel-sized lookups
  *rays = path->rays;
  return true;
}

// Keeps what bounce k did: the path ends where it stopped or after its last bounce.
inline void store_queued_path(__global QueuedPath* path, uint k, uint later_bounces, bool goes_on, HitSurface* h,
                              float3 dir, float3 throughput, float3 sum, uint rays) {
  vstore3(sum, 0, path->sum);
  path->rays = rays;
  if (!goes_on || k + 1u == later_bounces) {
    path->mode |= PATH_ENDED;
    return;
  }
  // The surface it now stands on, as the trace gave it: hit_surface builds it again for the next bounce.
  path->prim = h->hit.prim;
  path->u = h->hit.u;
  path->v = h->hit.v;
  vstore3(dir, 0, path->dir);
  vstore3(throughput, 0, path->throughput);
}

// A path's whole light, from first (its first hit's, as the sample kept it) and what its bounces gathered.
inline float3 queued_path_light(__global const QueuedPath* path, float3 first) {
  const float3 sum = vload3(0, path->sum);
  return (path->mode & ~PATH_ENDED) == PATH_READS_RECORDS ? finite_or_zero(sum) : first + finite_or_zero(sum);
}

#endif
