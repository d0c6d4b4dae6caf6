// Rays counted, and in the wavefront trace queued (GroupSizes::record_trace; host/passes/ray_queue.h). Every function
// that traces takes a RayTally* and traces through visible() (kernels/lighting.h) or closest_hit (below), which ask
// traced_or_queued first.
//
// RAYS_TRACED: every ray is traced where it is asked for (one-kernel shading, the direct pass, the path tracer).
// The wavefront instead launches its shading kernel in rounds around a kernel that traces the queue:
// RAYS_QUEUED: the work's k-th ray takes slot first_slot + k; one already answered there is read, one not yet is queued
//   and answered for now as unblocked or a miss. The round's results are thrown away: it only lists rays.
// RAYS_ANSWERED: the last round reads every answer; a ray still unanswered is traced where asked for.
// Every ray's answer is the same bits as a trace where asked for (the same ray_precompute and bvh_trace), so each round
// replays the same float operations. That needs one thing of the shading: whether and which rays it asks for may
// depend on an earlier ray's answer only through a closest hit (a path's next surface), never through a shadow ray's
// (a light's value is zeroed, its control flow unchanged). A closest hit answered "miss" for now ends the path there;
// its next round, with that answer read, asks for the rays beyond. So a path's bounce takes three rounds: the next
// surface, its shadow rays, then the light. Rays past slot_count (scenes with many lights) are traced where asked for
// in every round.
#ifndef RCSPLAT_RAY_QUEUE_H
#define RCSPLAT_RAY_QUEUE_H
#include "traverse.h"

typedef struct {
  uint cast;  // rays cast (or queued to be) so far: the summary's count, the same in every round and mode
  uint mode;  // RAYS_TRACED ..
  uint next, slot_count;  // the work's next ray's slot, and how many slots it has
  size_t first_slot;
  __global QueuedRay* queue;
  volatile __global uint* queue_length;  // [0] the queue's length, [1] rays the last round had to trace itself
  __global const HitDesc* answers;
} RayTally;

inline RayTally traced_rays(uint cast) {
  RayTally t;
  t.cast = cast;
  t.mode = RAYS_TRACED;
  t.next = t.slot_count = 0u;
  t.first_slot = 0;
  t.queue = 0;
  t.queue_length = 0;
  t.answers = 0;
  return t;
}

// A wavefront shading kernel's ray queue parameters (RAY_QUEUE_ARGS) and the tally of work `work`'s rays in them.
#define RAY_QUEUE_ARGS                                                                                             \
  __global QueuedRay *ray_queue, volatile __global uint *ray_queue_length, __global const HitDesc *ray_answers,     \
      uint ray_slots, uint ray_mode
inline RayTally queued_rays(RAY_QUEUE_ARGS, size_t work, uint cast) {
  RayTally t = traced_rays(cast);
  t.mode = ray_mode;
  t.slot_count = ray_slots;
  t.first_slot = work * ray_slots;
  t.queue = ray_queue;
  t.queue_length = ray_queue_length;
  t.answers = ray_answers;
  return t;
}
#define RAY_QUEUE ray_queue, ray_queue_length, ray_answers, ray_slots, ray_mode

// Whether the round writes what it shaded (RAYS_QUEUED rounds only list rays).
inline bool rays_answered(const RayTally* rays) { return rays->mode != RAYS_QUEUED; }

// Counts the ray and, where the queue answers it, gives its answer in *answer and returns true; false: trace it here.
inline bool traced_or_queued(RayTally* rays, float3 origin, float3 direction, float tmax, bool closest,
                             HitDesc* answer) {
  ++rays->cast;
  if (rays->mode == RAYS_TRACED || rays->next >= rays->slot_count) return false;
  const size_t slot = rays->first_slot + rays->next++;
  const HitDesc known = rays->answers[slot];
  if (known.prim != RAY_UNANSWERED) {
    *answer = known;
    return true;
  }
  if (rays->mode != RAYS_QUEUED) {
    atomic_inc(rays->queue_length + 1);  // rounds too few for this shading: counted for the tests, which expect none
    return false;
  }
  QueuedRay q;
  vstore3(origin, 0, q.origin);
  q.tmax = tmax;
  vstore3(direction, 0, q.direction);
  q.slot = (uint)slot | (closest ? QUEUED_RAY_CLOSEST : 0u);
  rays->queue[atomic_inc(rays->queue_length)] = q;
  const HitDesc for_now = {INFINITY, 0.0f, 0.0f, -1};
  *answer = for_now;
  return true;
}

// The closest hit along the unit direction dir from origin, counted in *rays and answered by the queue where it can.
inline bool closest_hit(BVH_ARGS, RayTally* rays, float3 origin, float3 dir, TraceHit* hit) {
  HitDesc answer;
  if (traced_or_queued(rays, origin, dir, INFINITY, true, &answer)) {
    hit->t = answer.t;
    hit->u = answer.u;
    hit->v = answer.v;
    hit->prim = answer.prim;
    return answer.prim >= 0;
  }
  RayPrecomp r = ray_precompute(origin, dir);
  return bvh_trace(BVH, &r, 0.0f, INFINITY, false, hit);
}

#endif
