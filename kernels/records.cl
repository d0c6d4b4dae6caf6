// Record computation (docs/ALGORITHM.md sections 4 and 5): for each candidate pixel, M x N stratified cosine-weighted rays
// over the hemisphere of its G-buffer point give the irradiance E, the validity radius (Ward's harmonic mean distance,
// or with hessian_error the occlusion Hessian's; clamped in screen space) and Ward & Heckbert's rotational and
// translational gradients, bounded.
//
// The work is spread over rays, not only over records (a coarse placement level has a few hundred records but a
// hundred thousand rays, and a GPU needs that many work-items in flight), in three kernels per launch of candidates:
//   aim_record_guides   per record: the light guide's cones its rays share (none without a guide);
//   trace_record_rays   per ray: one stratum's radiance and hit distance, or one guided ray's weighted share of E
//                       (or the same in two kernels, trace_record_hits and shade_record_hits, or as a wavefront,
//                       trace_record_hits, shade_record_first_hits and a kernel a later bounce over a queue of paths:
//                       GroupSizes::record_trace, the device's choice);
//   reduce_records      per record: E, the radius, the gradients and the horizon from its samples, summed in one fixed
//                       order, so a record does not depend on how its rays were scheduled (the radius' Hessian
//                       walks its own mesh of the samples: relative_irradiance_hessian).
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "bounce.h"
#include "cache_math.h"
#include "light_guide.h"
#include "path_queue.h"
#include "record_hessian.h"

// The host compiles this file with THETA_STRATA_CAPACITY = the largest M it will ask for (at most
// HEMISPHERE_MAX_THETA_STRATA): reduce_records keeps one column of M strata in private memory. With STORE_STRATA = 1
// (radiance caching) the samples buffer is the batch's strata, kept for the HSH projection of
// kernels/hsh_records.cl, and records cast no guided rays (each pixel samples the guide's share, kernels/glossy.cl).

// Samples per record: its M x N strata, then its guided rays.
inline uint record_sample_count(HemisphereParams hp) {
#if STORE_STRATA
  return hp.theta_strata * hp.phi_strata;
#else
  return hp.theta_strata * hp.phi_strata + hp.guide_rays;
#endif
}

// Where a record sits and the frame its strata are laid out in (the horizon sectors are measured in it too).
typedef struct {
  float3 p, n, ng, origin, t, b;
  uint key;  // the record's random stream
} RecordSite;

inline RecordSite record_site(__global const GBufferSample* gbuffer, uint pixel, uint seed) {
  GBufferSample g = gbuffer[pixel];
  RecordSite site;
  site.p = vload3(0, g.position);
  site.n = vload3(0, g.normal);
  site.ng = vload3(0, g.geometric_normal);
  site.origin = offset_ray_origin(site.p, site.ng);
  tangent_frame(site.n, &site.t, &site.b);
  site.key = hash_u32(pixel ^ hash_u32(seed));
  return site;
}

// n_c p_c / cos(theta): the strata's cosine density, per unit of cos(theta).
inline float strata_cosine_density(HemisphereParams hp) {
  return (float)(hp.theta_strata * hp.phi_strata) * RC_INV_PI;
}

// sin^2(theta) of stratum s's ray (row j = s / N): the trace draws it, the reduction needs it again for the horizon.
inline float stratum_sin2_theta(HemisphereParams hp, uint key, uint s) {
  return ((float)(s / hp.phi_strata) + random01(key, s, 0u)) * (1.0f / (float)hp.theta_strata);
}

// gradient[axis] += direction[axis] * value, for a world-space direction and an RGB value.
inline void add_outer(float3* gradient, float3 direction, float3 value) {
  gradient[0] += direction.x * value;
  gradient[1] += direction.y * value;
  gradient[2] += direction.z * value;
}

// Scales the per-channel gradient rows so that no channel's gradient is longer than limit (per channel).
inline void bound_gradient(float3* gradient, float3 limit) {
  float3 len = sqrt(gradient[0] * gradient[0] + gradient[1] * gradient[1] + gradient[2] * gradient[2]);
  float3 scale = select((float3)(1.0f), limit / len, len > limit);
  for (int a = 0; a < 3; ++a) gradient[a] = finite_or_zero(gradient[a] * scale);
}

// Stratum s's ray direction (row j = s / N, column k = s % N), jittered in its stratum by the record's stream.
inline float3 stratum_direction(RecordSite site, HemisphereParams hp, uint s) {
  const uint N = hp.phi_strata, k = s % N;
  float sin2 = stratum_sin2_theta(hp, site.key, s);
  float sin_t = sqrt(sin2), cos_t = sqrt(1.0f - sin2);
  float cos_phi, sin_phi = sincos(((float)k + random01(site.key, s, 1u)) * (2.0f * RC_PI / (float)N), &cos_phi);
  return (cos_phi * sin_t) * site.t + (sin_phi * sin_t) * site.b + cos_t * site.n;
}

// Sample s of a record: the direction of its ray and the balance heuristic's factor of the radiance the ray brings.
typedef struct {
  float3 dir;
  float weight;
  bool cast;     // false: no ray is cast, the sample is zero
  bool stratum;  // a stratum keeps its hit distance (INFINITY where nothing is hit or no ray is cast); a guided ray 0
} RecordRay;

// Stratum s = j N + k: a cosine-weighted ray in row j, column k. It brings the share of the light the guide leaves to
// the strata (the balance heuristic beside the guided rays, kernels/light_guide.h). A direction below the geometric
// surface casts no ray: it sees nothing.
inline RecordRay stratum_ray(RecordSite site, HemisphereParams hp, uint s, __global const RecordGuideCones* cones) {
  RecordRay ray;
  ray.stratum = true;
  ray.dir = stratum_direction(site, hp, s);
  ray.cast = dot(ray.dir, site.ng) > 0.0f;
  ray.weight = 1.0f;
  if (stored_cone_count(cones)) {
    float c = strata_cosine_density(hp) * sqrt(1.0f - stratum_sin2_theta(hp, site.key, s));
    ray.weight = c / (c + (float)hp.guide_rays * stored_guide_pdf_drawn(cones, ray.dir, GUIDE_MAX_CONES));
  }
  return ray;
}

// Guided ray s (s >= M N) into the record's cones, weighted f / (n_c p_c + n_g p_g) with f = L cos(theta): its share
// of E. None where the record has no cones. The guided rays are point s - M N of a net scrambled per record
// (kernels/low_discrepancy.h): its first coordinate picks the cone, the other two the direction in it. Independent
// numbers gave the built-in Cornell box 1.04x / 1.02x the relMSE / block error at 16 x 32 and 1.29x / 1.27x at 8 x
// 16, and the corridor three times the block error, at the same rays (RESULTS.md "Issue 13, twelfth step").
inline RecordRay guided_ray(RecordSite site, HemisphereParams hp, uint s, __global const RecordGuideCones* cones) {
  RecordRay ray;
  ray.stratum = ray.cast = false;
  ray.dir = site.n;
  ray.weight = 0.0f;
  if (!stored_cone_count(cones)) return ray;
  uint drawn_from;
  float u, v, w;
  scrambled_sobol3(s - hp.theta_strata * hp.phi_strata, site.key, &u, &v, &w);
  ray.dir = sample_stored_guide(cones, u, v, w, &drawn_from);
  float cos_n = dot(ray.dir, site.n);
  if (cos_n <= 0.0f || dot(ray.dir, site.ng) <= 0.0f) return ray;
  ray.cast = true;
  ray.weight = cos_n / (strata_cosine_density(hp) * cos_n +
                        (float)hp.guide_rays * stored_guide_pdf_drawn(cones, ray.dir, drawn_from));
  return ray;
}

inline RecordRay record_ray(RecordSite site, HemisphereParams hp, uint s, __global const RecordGuideCones* cones) {
  return s < hp.theta_strata * hp.phi_strata ? stratum_ray(site, hp, s, cones) : guided_ray(site, hp, s, cones);
}

// Sample s as the reduction reads it, (weighted radiance, hit distance), from the radiance l its ray brought from
// `distance` away.
inline float4 record_sample(RecordRay ray, float3 l, float distance) {
  if (!ray.cast) return (float4)(0.0f, 0.0f, 0.0f, ray.stratum ? INFINITY : 0.0f);
  return (float4)(l * ray.weight, ray.stratum ? distance : 0.0f);
}

// The light guide's cones for each record of the launch (none without a guide): its rays and its strata are weighted
// by the balance heuristic, each sample's weight its technique's share of the combined density n_c p_c + n_g p_g.
__kernel void aim_record_guides(GBUFFER_ARGS, __global const uint* candidates, RecordBatchParams batch,
                                __global const GuideCluster* guide, __global RecordGuideCones* record_guides) {
  uint q = get_global_id(0);
  if (q >= batch.launch_count) return;
  const HemisphereParams hp = batch.hemisphere;
  GBufferSample g = gbuffer[candidates[batch.first_candidate + q]];
  GuideCone cones[GUIDE_MAX_CONES];
  // A cone larger than GUIDE_MAX_STRATA strata' worth of solid angle is found often enough by the strata themselves.
  uint count = hp.guide_rays ? guide_cones(guide, hp.guide_clusters, vload3(0, g.position), vload3(0, g.normal),
                                           GUIDE_MAX_STRATA / strata_cosine_density(hp), cones)
                             : 0u;
  store_guide_cones(cones, count, record_guides + q);
}

// A work-item of the record trace takes batch.samples_per_item consecutive samples of one of the launch's records
// (candidate first_candidate + q): a GPU one sample a work-item, a CPU device several, sharing the record's site.
typedef struct {
  uint q, first, end;  // the launch's record q, its samples first .. end - 1
  uint per_record;     // samples a record takes
  RecordSite site;
} RecordItem;

inline bool record_item(__global const GBufferSample* gbuffer, __global const uint* candidates,
                        RecordBatchParams batch, RecordItem* item) {
  const uint per_record = record_sample_count(batch.hemisphere), per_item = batch.samples_per_item;
  const uint items_per_record = (per_record + per_item - 1) / per_item;
  uint id = get_global_id(0);
  item->q = id / items_per_record;
  item->first = (id - item->q * items_per_record) * per_item;
  item->end = min(item->first + per_item, per_record);
  item->per_record = per_record;
  if (item->q >= batch.launch_count) return false;
  item->site = record_site(gbuffer, candidates[batch.first_candidate + item->q], batch.hemisphere.seed);
  return true;
}

// Where the item's record starts in the samples buffer (stored strata keep the whole batch's) and in the launch's
// per-sample buffers (rays cast, hits).
inline size_t record_samples_at(RecordBatchParams batch, RecordItem item) {
  return (size_t)(batch.first_candidate + item.q - batch.samples_first_candidate) * item.per_record;
}
inline size_t record_launch_at(RecordItem item) { return (size_t)item.q * item.per_record; }

// Sample s's ray traced to its closest hit (prim -1: a miss, -2: no ray cast).
inline HitDesc trace_record_hit(SCENE_ARGS, RecordSite site, RecordRay ray) {
  TraceHit hit = {INFINITY, 0.0f, 0.0f, -2};
  if (ray.cast) {
    RayPrecomp r = ray_precompute(site.origin, ray.dir);
    if (!bvh_trace(BVH, &r, 0.0f, INFINITY, false, &hit)) hit.prim = -1;
  }
  HitDesc out = {hit.t, hit.u, hit.v, hit.prim};
  return out;
}

// The light sample s's ray brings from `hit` (kernels/bounce.h), unweighted; *rays counts the rays cast, its own
// included. A hit on glass (kernels/glass.h) goes on through it first: *hit becomes the first hit that is not glass
// (its t the chain's length), ray->dir the direction it arrives along, and *through_glass what the glass kept, which the
// light returned includes. queues_paths (the wavefront trace): only the first hit's light, *after saying what path
// must still go on from there (PATH_DONE ..); otherwise the whole path's.
inline float3 record_hit_light(SCENE_ARGS GATHER_MAP_ARGS, RecordSite site, HemisphereParams hp, uint s,
                               RecordRay* ray, HitDesc* hit, bool queues_paths, uint* after, float3* through_glass,
                               RayTally* rays) {
  rays->cast = ray->cast ? 1u : 0u;
  *after = PATH_DONE;
  *through_glass = (float3)(1.0f);
#if HAS_TRANSMISSION
  if (hit->prim >= 0) *through_glass = kept_hit_past_glass(BVH, rays, hit, &ray->dir);
#endif
  if (hit->prim < 0) return ray->cast ? miss_radiance(SCENE, ray->dir) * *through_glass : (float3)(0.0f);
  // The ray's cone: the solid angle of its stratum, 2 pi / (M N), as an angle (ray cones: kernels/surface.h).
  const float cone = sqrt(2.0f * RC_PI / (float)(hp.theta_strata * hp.phi_strata));
  HitSurface h = hit_surface(HIT_SURFACE, hit->prim, hit->u, hit->v, ray->dir, hit->t * cone);
  const PathContinuation more = path_continuation(site.key, s, hp.bounces);
  const float u = random01(site.key, s, 2u), v = random01(site.key, s, 3u), u_lobe = random01(site.key, s, 4u);
  if (queues_paths)
    return first_bounce_from_hit(SCENE GATHER_MAP, &h, ray->dir, hit->t, u, v, u_lobe, more, rays, after) *
           *through_glass;
  return radiance_from_hit(SCENE GATHER_MAP, &h, ray->dir, hit->t, u, v, u_lobe, more, rays) * *through_glass;
}

// Sample s from the light its ray brings from `hit`, its whole path's.
inline float4 shade_record_hit(SCENE_ARGS GATHER_MAP_ARGS, RecordSite site, HemisphereParams hp, uint s,
                               RecordRay ray, HitDesc hit, RayTally* rays) {
  uint after;
  float3 through_glass;
  float3 l = record_hit_light(SCENE GATHER_MAP, site, hp, s, &ray, &hit, false, &after, &through_glass, rays);
  return record_sample(ray, l, hit.prim >= 0 ? hit.t : INFINITY);
}

// Each sample's ray traced and shaded in one work-item (a CPU device: a work-item's samples share their record's
// site)...
__kernel void trace_record_rays(SCENE_ARGS GATHER_MAP_ARGS, GBUFFER_ARGS, __global const uint* candidates,
                                RecordBatchParams batch, __global const RecordGuideCones* record_guides,
                                __global float4* samples, __global uint* sample_rays) {
  RecordItem item;
  if (!record_item(gbuffer, candidates, batch, &item)) return;
  for (uint s = item.first; s < item.end; ++s) {
    RecordRay ray = record_ray(item.site, batch.hemisphere, s, record_guides + item.q);
    HitDesc hit = trace_record_hit(SCENE, item.site, ray);
    RayTally rays = traced_rays(0u);
    samples[record_samples_at(batch, item) + s] =
        shade_record_hit(SCENE GATHER_MAP, item.site, batch.hemisphere, s, ray, hit, &rays);
    sample_rays[record_launch_at(item) + s] = rays.cast;
  }
}

// ... or in two kernels, each with less to hold in registers (a GPU: in one, a hemisphere ray with its hit's shading,
// shadow ray and photon lookup took NVIDIA's 255 registers and spilled). The samples are the same, bit for bit:
// trace_record_hits keeps each sample's hit...
__kernel void trace_record_hits(SCENE_ARGS, GBUFFER_ARGS, __global const uint* candidates, RecordBatchParams batch,
                                __global const RecordGuideCones* record_guides, __global HitDesc* hits) {
  RecordItem item;
  if (!record_item(gbuffer, candidates, batch, &item)) return;
  for (uint s = item.first; s < item.end; ++s) {
    RecordRay ray = record_ray(item.site, batch.hemisphere, s, record_guides + item.q);
    hits[record_launch_at(item) + s] = trace_record_hit(SCENE, item.site, ray);
  }
}

// ... and shade_record_hits shades them (the sample's direction and weight found again: cheaper than storing them).
__kernel void shade_record_hits(SCENE_ARGS GATHER_MAP_ARGS, GBUFFER_ARGS, __global const uint* candidates,
                                RecordBatchParams batch, __global const RecordGuideCones* record_guides,
                                __global const HitDesc* hits, __global float4* samples, __global uint* sample_rays) {
  RecordItem item;
  if (!record_item(gbuffer, candidates, batch, &item)) return;
  for (uint s = item.first; s < item.end; ++s) {
    RecordRay ray = record_ray(item.site, batch.hemisphere, s, record_guides + item.q);
    RayTally rays = traced_rays(0u);
    samples[record_samples_at(batch, item) + s] = shade_record_hit(
        SCENE GATHER_MAP, item.site, batch.hemisphere, s, ray, hits[record_launch_at(item) + s], &rays);
    sample_rays[record_launch_at(item) + s] = rays.cast;
  }
}

// ... or, the wavefront trace (GroupSizes::record_trace, a GPU), in small kernels of which none holds a path's loop
// (kernels/path_queue.h). shade_record_first_hits shades each hit as far as its first bounce's light, and queues the
// paths that must go on from there, their samples waiting unweighted...
__kernel void shade_record_first_hits(SCENE_ARGS GATHER_MAP_ARGS, GBUFFER_ARGS, __global const uint* candidates,
                                      RecordBatchParams batch, __global const RecordGuideCones* record_guides,
                                      __global const HitDesc* hits, __global float4* samples,
                                      __global uint* sample_rays, __global QueuedPath* paths,
                                      volatile __global uint* path_count, RAY_QUEUE_ARGS) {
  RecordItem item;
  if (!record_item(gbuffer, candidates, batch, &item)) return;
  for (uint s = item.first; s < item.end; ++s) {
    RecordRay ray = record_ray(item.site, batch.hemisphere, s, record_guides + item.q);
    const size_t at = record_samples_at(batch, item) + s, launch_at = record_launch_at(item) + s;
    HitDesc hit = hits[launch_at];
    uint after;
    float3 through_glass;
    RayTally rays = queued_rays(RAY_QUEUE, launch_at, 0u);
    float3 l = record_hit_light(SCENE GATHER_MAP, item.site, batch.hemisphere, s, &ray, &hit, true, &after,
                                &through_glass, &rays);
    if (!rays_answered(&rays)) continue;
    float4 sample = record_sample(ray, l, hit.prim >= 0 ? hit.t : INFINITY);
    if (after == PATH_DONE) {
      samples[at] = sample;
      sample_rays[launch_at] = rays.cast;
    } else {
      samples[at] = (float4)(l, sample.w);
      const PathContinuation more = path_continuation(item.site.key, s, batch.hemisphere.bounces);
      queue_path(paths, path_count, (uint)at, (uint)launch_at, more, after, hit, ray.dir, (float3)(0.0f), through_glass,
                 ray.weight, rays.cast);
    }
  }
}

// ... step_record_paths takes every queued path bounce `bounce` further (0 .. later_bounces - 1, a launch each)...
__kernel void step_record_paths(SCENE_ARGS GATHER_MAP_ARGS, __global QueuedPath* paths,
                                __global const uint* path_count, uint bounce, uint later_bounces, RAY_QUEUE_ARGS) {
  const size_t i = get_global_id(0);
  HitSurface h;
  float3 dir, throughput, sum;
  PathContinuation more;
  RayTally rays = queued_rays(RAY_QUEUE, i, 0u);
  if (i >= *path_count ||
      !load_queued_path(HIT_SURFACE, paths + i, later_bounces, &h, &dir, &throughput, &sum, &more, &rays.cast))
    return;
  bool goes_on = path_bounce(SCENE GATHER_MAP, &h, &dir, &throughput, more, bounce, paths[i].mode, &sum, &rays);
  if (rays_answered(&rays))
    store_queued_path(paths + i, bounce, later_bounces, goes_on, &h, dir, throughput, sum, rays.cast);
}

// ... and finish_record_paths adds each path's light to its sample and weighs it, as shade_record_hit does.
__kernel void finish_record_paths(__global const QueuedPath* paths, __global const uint* path_count,
                                  __global float4* samples, __global uint* sample_rays) {
  const size_t i = get_global_id(0);
  if (i >= *path_count) return;
  __global const QueuedPath* path = paths + i;
  const float4 first = samples[path->sample];
  samples[path->sample] = (float4)(queued_path_light(path, first.xyz) * path->weight, first.w);
  sample_rays[path->launch_sample] = path->rays;
}

// The Hessian's mesh takes every row_step-th row (ending at the last, nearest the horizon) and every column_step-th
// column of the strata, HESSIAN_MESH_SIDE of each where they divide evenly. Measured (RESULTS "Record radii"): the
// whole 16 x 32 mesh (1,500 edges) cost a quarter more record time on Sponza for no less error than a 4 x 4 one
// (40 edges), which costs about nothing beside the rays; single strata's noise reads as curvature anyway.
#define HESSIAN_MESH_SIDE 4
typedef struct {
  uint rows, row_first, row_step, columns, column_step;
} HessianMesh;

inline uint hessian_mesh_step(uint strata) {
  uint step = strata / HESSIAN_MESH_SIDE;
  return step > 1 && strata % step == 0 ? step : 1u;
}

inline HessianMesh hessian_mesh(HemisphereParams hp) {
  HessianMesh m;
  m.row_step = hessian_mesh_step(hp.theta_strata);
  m.rows = hp.theta_strata / m.row_step;
  m.row_first = hp.theta_strata - 1 - (m.rows - 1) * m.row_step;
  m.column_step = hessian_mesh_step(hp.phi_strata);
  m.columns = hp.phi_strata / m.column_step;
  return m;
}

// Mesh column c's hit points relative to the record's origin (xyz, distance in w) and their relative values.
// Distances are held in [near, far]: misses go far beyond the scene, and hits nearer than near (whose 1/d^6 terms
// would overflow float) count as at near, where the radius' lower clamp rules anyway.
inline void hessian_mesh_column(__global const float4* own, RecordSite site, HemisphereParams hp, HessianMesh mesh,
                                uint c, float near, float far, float value_scale, float value_floor, float4* points,
                                float* values) {
  for (uint m = 0; m < mesh.rows; ++m) {
    uint s = (mesh.row_first + m * mesh.row_step) * hp.phi_strata + c * mesh.column_step;
    float4 sample = own[s];
    float d = clamp(sample.w, near, far);
    points[m] = (float4)(d * stratum_direction(site, hp, s), d);
    values[m] = luminance(sample.xyz) * value_scale + value_floor;
  }
}

// The value a triangle of the mesh takes: its farthest vertex's (Schwarzhaupt et al.: a triangle spanning a depth
// step shows the background, not the occluder's edge).
inline float back_value(float4 p0, float v0, float4 p1, float v1, float4 p2, float v2) {
  float v = p1.w > p0.w ? v1 : v0, d = fmax(p0.w, p1.w);
  return p2.w > d ? v2 : v;
}

// The tangent-plane Hessian of the record's relative irradiance (E over the strata's mean, per world length^2), from
// the mesh its strata's hits make (hessian_mesh). Vertices V(j, k) (mesh row j, mesh column k, k wrapping); each cell
// between rows j and j + 1 and columns k and k + 1 holds triangles A = V(j,k) V(j+1,k) V(j,k+1) and
// B = V(j+1,k+1) V(j,k+1) V(j+1,k), and row 0 closes into one polygon around the zenith (the cap, its vertices' mean
// value). Each edge is evaluated once, weighted by the difference of the values on its two sides; the gap below the
// last row (half a stratum above the horizon) is left open, as Schwarzhaupt et al. leave theirs. Values are luminance
// over the strata's mean, times 0.99, plus 0.01 (their robust relative metric: black occluders before black still
// count); all 1 where the strata saw no light at all, which leaves the geometric Hessian.
// luminance_sum: of all the strata's radiance (the reduction has summed it already).
inline TangentBlock relative_irradiance_hessian(__global const float4* own, RecordSite site, HemisphereParams hp,
                                                float luminance_sum, float near, float far) {
  const uint strata = hp.theta_strata * hp.phi_strata;
  float value_scale = 0.0f, value_floor = 1.0f;
  if (luminance_sum > 0.0f && isfinite(luminance_sum)) {
    value_scale = 0.99f * (float)strata / luminance_sum;
    value_floor = 0.01f;
  }
  const HessianMesh mesh = hessian_mesh(hp);
  const uint M = mesh.rows, N = mesh.columns;
  float4 first_p[THETA_STRATA_CAPACITY], cur_p[THETA_STRATA_CAPACITY], next_p[THETA_STRATA_CAPACITY];
  float first_v[THETA_STRATA_CAPACITY], cur_v[THETA_STRATA_CAPACITY], next_v[THETA_STRATA_CAPACITY];
  float first_a[THETA_STRATA_CAPACITY], prev_b[THETA_STRATA_CAPACITY];  // A(j, 0); B(j, k - 1)
  hessian_mesh_column(own, site, hp, mesh, 0, near, far, value_scale, value_floor, first_p, first_v);
  float cap = 0.0f;
  for (uint k = 0; k < N; ++k)
    cap += luminance(own[mesh.row_first * hp.phi_strata + k * mesh.column_step].xyz) * value_scale + value_floor;
  cap /= (float)N;
  for (uint j = 0; j < M; ++j) {
    cur_p[j] = first_p[j];
    cur_v[j] = first_v[j];
  }
  const float3 n = site.n, t = site.t, b = site.b;
  TangentBlock h = (TangentBlock)(0.0f);
  for (uint k = 0; k < N; ++k) {
    if (k + 1 < N) hessian_mesh_column(own, site, hp, mesh, k + 1, near, far, value_scale, value_floor, next_p, next_v);
    else
      for (uint j = 0; j < M; ++j) {
        next_p[j] = first_p[j];
        next_v[j] = first_v[j];
      }
    float above = cap;  // the value above row j's edge V(j,k) V(j,k+1): the cap, then B(j - 1, k)
    for (uint j = 0; j + 1 < M; ++j) {
      float va = back_value(cur_p[j], cur_v[j], cur_p[j + 1], cur_v[j + 1], next_p[j], next_v[j]);
      float vb = back_value(next_p[j + 1], next_v[j + 1], next_p[j], next_v[j], cur_p[j + 1], cur_v[j + 1]);
      h += (va - vb) * edge_form_factor_hessian(cur_p[j + 1].xyz, next_p[j].xyz, n, t, b);  // the diagonal
      h += (above - va) * edge_form_factor_hessian(cur_p[j].xyz, next_p[j].xyz, n, t, b);    // row j's edge
      if (k > 0) h += (va - prev_b[j]) * edge_form_factor_hessian(cur_p[j].xyz, cur_p[j + 1].xyz, n, t, b);
      else first_a[j] = va;
      prev_b[j] = vb;
      above = vb;
    }
    h += above * edge_form_factor_hessian(cur_p[M - 1].xyz, next_p[M - 1].xyz, n, t, b);  // the open bottom row
    for (uint j = 0; j < M; ++j) {
      cur_p[j] = next_p[j];
      cur_v[j] = next_v[j];
    }
  }
  for (uint j = 0; j + 1 < M; ++j)  // column 0's edges between A(j, 0) and B(j, N - 1)
    h += (first_a[j] - prev_b[j]) * edge_form_factor_hessian(first_p[j].xyz, first_p[j + 1].xyz, n, t, b);
  return h;
}

// One work-item per record of the launch: its samples reduced in the order of the strata (columns k, rows j within),
// then its guided rays.
__kernel void reduce_records(GBUFFER_ARGS, __global const uint* candidates, RecordBatchParams batch,
                             __global const float4* samples, __global const uint* sample_rays,
                             __global CacheRecord* records, __global ulong* ray_total) {
  uint q = get_global_id(0);
  if (q >= batch.launch_count) return;
  const HemisphereParams hp = batch.hemisphere;
  const uint i = batch.first_candidate + q, pixel = candidates[i], per_record = record_sample_count(hp);
  RecordSite site = record_site(gbuffer, pixel, hp.seed);
  __global const float4* own = samples + (size_t)(i - batch.samples_first_candidate) * per_record;
  __global const uint* own_rays = sample_rays + (size_t)q * per_record;
  const uint M = hp.theta_strata, N = hp.phi_strata;
  const float inv_m = 1.0f / (float)M, dphi = 2.0f * RC_PI / (float)N;

  // Per-row weights, the same in every column: computed once. theta_wall: the wall between rows j - 1 and j, at
  // theta_j- (sin theta cos^2 theta dphi); phi_wall: the integral of cos(theta) over row j (the walls between columns);
  // rotation: the integral of sin^2(theta) over row j. Tilting n by d about axis a changes E by d times the integral
  // of L sin(theta) (a . v(phi)) dw; integrating that weight over each stratum (rather than Ward and Heckbert's
  // per-sample tan(theta), whose variance is unbounded in the row at the horizon) leaves no gradient at all in a
  // uniform environment.
  float theta_wall[THETA_STRATA_CAPACITY], phi_wall[THETA_STRATA_CAPACITY], rotation_weight[THETA_STRATA_CAPACITY];
  for (uint j = 0; j < M; ++j) {
    float sin_lo = sqrt((float)j * inv_m), cos_lo = sqrt(1.0f - (float)j * inv_m);
    float sin_hi = sqrt((float)(j + 1) * inv_m), cos_hi = sqrt(fmax(1.0f - (float)(j + 1) * inv_m, 0.0f));
    theta_wall[j] = dphi * sin_lo * cos_lo * cos_lo;
    phi_wall[j] = sin_hi - sin_lo;
    rotation_weight[j] = 0.5f * (asin(sin_hi) - asin(sin_lo)) - 0.5f * (sin_hi * cos_hi - sin_lo * cos_lo);
  }

  // Stratum (j, k) needs (j - 1, k) and (j, k - 1): keep the previous column, and the first for the wrap-around.
  float3 prev_l[THETA_STRATA_CAPACITY], first_l[THETA_STRATA_CAPACITY];
  float prev_r[THETA_STRATA_CAPACITY], first_r[THETA_STRATA_CAPACITY];
  float3 e = (float3)(0.0f);
  float3 grad_t[3] = {(float3)(0.0f), (float3)(0.0f), (float3)(0.0f)};
  float3 grad_r[3] = {(float3)(0.0f), (float3)(0.0f), (float3)(0.0f)};
  float inverse_distances = 0.0f;
  // Collapsed strata (Cochran, Sampling Techniques 5A.12): columns k - 1 and k (k odd) pair up row by row, and the
  // squared differences of their luminance estimate the sum's variance (conservatively: the pair's own slope counts).
  float pair_variance = 0.0f;
  // The horizon: per column, the nearest occluder the low rows (elevation below 30 degrees) found, measured along the
  // tangent plane; per sector, the nearest of its columns' (conservative: a wall seen obliquely hides the whole sector
  // beyond it).
  const uint first_low_row = (uint)ceil(HORIZON_MIN_SIN2_THETA * (float)M);
  float horizon[RECORD_HORIZON_SECTORS];
  for (int s = 0; s < RECORD_HORIZON_SECTORS; ++s) horizon[s] = INFINITY;
  ulong rays = 0;
  for (uint k = 0; k < N; ++k) {
    float cos_mid, sin_mid = sincos(((float)k + 0.5f) * dphi, &cos_mid);
    float cos_lo, sin_lo = sincos((float)k * dphi, &cos_lo);
    float3 u_mid = cos_mid * site.t + sin_mid * site.b, v_mid = -sin_mid * site.t + cos_mid * site.b,
           v_lo = -sin_lo * site.t + cos_lo * site.b;
    float3 rotation = (float3)(0.0f), l_below = (float3)(0.0f);
    float r_below = INFINITY, column_horizon = INFINITY;
    for (uint j = 0; j < M; ++j) {
      uint s = j * N + k;
      float4 sample = own[s];
      float3 l = sample.xyz;
      float r = sample.w;
      rays += own_rays[s];
      e += l;
      inverse_distances += 1.0f / r;
      if (j >= first_low_row) column_horizon = fmin(column_horizon, r * sqrt(stratum_sin2_theta(hp, site.key, s)));
      rotation += rotation_weight[j] * l;
      if (j > 0) add_outer(grad_t, u_mid, (theta_wall[j] / fmin(r, r_below)) * (l - l_below));
      if (k & 1u) {
        float d = luminance(l) - luminance(prev_l[j]);
        pair_variance += d * d;
      }
      if (k > 0) add_outer(grad_t, v_lo, (phi_wall[j] / fmin(r, prev_r[j])) * (l - prev_l[j]));
      else {
        first_l[j] = l;
        first_r[j] = r;
      }
      l_below = l;
      r_below = r;
      prev_l[j] = l;
      prev_r[j] = r;
    }
    add_outer(grad_r, v_mid, (2.0f * sin(0.5f * dphi)) * rotation);  // the integral of v(phi) over the column
    int sector = horizon_sector(cos_mid, sin_mid);
    horizon[sector] = fmin(horizon[sector], column_horizon);
  }
  for (uint j = 0; j < M; ++j)  // the wall at phi = 0 between the last column and the first
    add_outer(grad_t, site.b, (phi_wall[j] / fmin(first_r[j], prev_r[j])) * (first_l[j] - prev_l[j]));
  float norm = RC_PI / (float)(M * N);
  float3 e_guided = (float3)(0.0f);
  for (uint s = M * N; s < per_record; ++s) {
    e_guided += own[s].xyz;
    rays += own_rays[s];
  }
  const float strata_luminance = luminance(e);  // before e becomes the irradiance
  e = finite_or_zero(e * norm + e_guided);
  // The strata's sum times norm is E's estimate: its standard error over E's luminance (infinite where E is black but
  // the strata were not; 0 where everything was black).
  const float error_sum = norm * sqrt(pair_variance), e_luminance = luminance(e);
  const float relative_error = error_sum > 0.0f ? (e_luminance > 0.0f ? error_sum / e_luminance : INFINITY) : 0.0f;

  // Radius: Ward's harmonic mean distance, or the occlusion Hessian's, clamped to [min, max] pixel footprints.
  float harmonic = (float)(M * N) / inverse_distances;
  float pixel_size = pixel_world_size(camera, site.p);
  float unclamped = harmonic;
  if (hp.hessian_error > 0.0f) {
    float near = 0.25f * pixel_size, far = 1e3f * hp.max_radius_pixels * pixel_size;
    TangentBlock hessian = relative_irradiance_hessian(own, site, hp, strata_luminance, near, far);
    float curvature = largest_curvature(hessian) * pixel_size * pixel_size;
    unclamped = curvature > 0.0f ? pixel_size * sqrt(sqrt(hp.hessian_error / curvature)) : INFINITY;
  }
  float radius = clamp(unclamped, hp.min_radius_pixels * pixel_size, hp.max_radius_pixels * pixel_size);
  if (!(radius > 0.0f)) radius = fmax(hp.min_radius_pixels * pixel_size, 1e-30f);
  // Bounded gradients (docs/ALGORITHM.md section 5): translation changes E by at most E across R, rotation by at most E.
  bound_gradient(grad_t, e / radius);
  bound_gradient(grad_r, e);

  CacheRecord rec;
  vstore3(site.p, 0, rec.position);
  rec.radius = radius;
  vstore3(site.n, 0, rec.normal);
  rec.pixel = (int)pixel;
  vstore3(e, 0, rec.irradiance);
  rec.pixel_size = pixel_size;
  for (int a = 0; a < 3; ++a) {
    vstore3(grad_t[a], a, rec.grad_translation);
    vstore3(grad_r[a], a, rec.grad_rotation);
  }
  rec.harmonic_distance = harmonic;
  rec.relative_error = relative_error;
  // A sector no column falls in (N < 8) hides nothing; a record always reaches its own pixel's half-footprint.
  for (int s = 0; s < RECORD_HORIZON_SECTORS; ++s)
    rec.horizon[s] = fmax(horizon[s], 0.5f * pixel_size);
  records[batch.first_record + i] = rec;
  atom_add(ray_total, rays);
}
