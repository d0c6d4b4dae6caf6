// Indirect light: what a ray leaving a surface sees, counted as the directly lit radiance reflected by the surface it
// lands on (never that surface's emission, which direct light already counts: docs/ALGORITHM.md section 1), and with
// --bounces N > 1 what the path continued from there gathers.
// Shared by the record pass and the path tracer so that both estimate the same integral.
#ifndef RCSPLAT_BOUNCE_H
#define RCSPLAT_BOUNCE_H
// First: reflected_light.h, included under #if below, includes it too.
#include "caustic_map.h"
#include "environment.h"
#include "lighting.h"
#include "scene_args.h"
#include "surface.h"
#if HAS_SPECULAR_BRDF
#include "reflected_light.h"
#endif

// PHOTON_GATHER = 1 (the record pass with --bounce-method photons): the bounces after the first come from the photon
// map (kernels/photon_map.h), which the kernels then take after SCENE_ARGS; otherwise from the continued path.
#ifndef CAUSTICS_APART
#define CAUSTICS_APART 0
#endif

// Included whatever PHOTON_GATHER says: kernel headers are include-once by name (host/cl/gpu_context.cpp), so a header
// inlined inside a false #if would be missing for a later file that includes it.
#include "photon_map.h"
#if PHOTON_GATHER
#define GATHER_MAP_ARGS , PHOTON_MAP_ARGS
#define GATHER_MAP , PHOTON_MAP
#else
#define GATHER_MAP_ARGS
#define GATHER_MAP
#endif

// The surface a ray from origin along *dir lands on, and its distance. Through glass (kernels/glass.h) the ray goes on
// to the first surface that is not glass, reflected or passed at each crossing: *dir becomes the direction it arrives
// along, *distance the chain's length, and *weight what the glass kept (1 without glass). false: the ray left the
// scene (along *dir). cone_angle: the ray cone's angle, for filtering the textures the hit reads (0: texel-sized).
inline bool trace_surface(SCENE_ARGS, float3 origin, float3* dir, float cone_angle, HitSurface* h, float* distance,
                          float3* weight, RayTally* rays) {
  TraceHit hit;
  *weight = (float3)(1.0f);
  if (!closest_hit(BVH, rays, origin, *dir, &hit)) {
    *distance = INFINITY;
    return false;
  }
  *distance = hit.t;
#if HAS_TRANSMISSION
  *weight = pass_glass(BVH, rays, &hit, dir, distance);
  if (hit.prim < 0) {
    *distance = INFINITY;
    return false;
  }
#endif
  *h = hit_surface(HIT_SURFACE, hit.prim, hit.u, hit.v, *dir, *distance * cone_angle);
  return true;
}

// The directly lit radiance the surface reflects back along -dir; (u, v) pick the light sample, u_lobe the lobe of its
// BRDF sample where the surface is glossy.
inline float3 hit_direct(SCENE_ARGS, HitSurface* h, float3 dir, float u, float v, float u_lobe, RayTally* rays) {
#if HAS_SPECULAR_BRDF
  const int lobe = hit_lobe_kind(materials, textures, texels, h);
  if (lobe != LOBE_NONE) {
    LazyBrdf brdf = lazy_hit_brdf(h);
    return direct_reflected(SCENE, &brdf, lobe, h->s.position, h->ns, h->ng, -dir, u, v, u_lobe, rays);
  }
#endif
  float3 e = direct_irradiance(BVH, lights, scene_counts.light_count, EMITTERS, scene_counts.emitter_count,
                               h->s.position, h->ns, h->ng, u, v, rays);
#if HAS_ENVIRONMENT
  float2 smooth_u = environment_extra_randoms(u, v, 0u), peak_u = environment_extra_randoms(u, v, 1u);
  e += environment_irradiance(SCENE, h->s.position, h->ns, h->ng, smooth_u.x, smooth_u.y, peak_u.x, peak_u.y, rays);
#endif
#if HAS_GLASS_CAUSTICS
  e += caustic_levels_irradiance(GLASS_CAUSTIC_MAP, h->s.position, h->ng, 0.0f);  // the light glass volumes passed
#endif
  if (!any_positive(e)) return (float3)(0.0f);  // what any albedo times it would give
  return finite_or_zero(hit_albedo(materials, textures, texels, h) * RC_INV_PI * e);
}

#if HAS_SPECULAR_BRDF
// What a record's ray finds lit directly on the surface it hits, less the light a sharp lobe (LOBE_GLOSSY) reflects of
// the sources the caustic map shoots photons from (punctual lights, emitters, the environment's peak): that path,
// light -> glossy -> the record's surface, is the caustic map's (kernels/caustic_map.cl), read at the pixels. A
// record counting it through its own ray made one stratum on a highlight carry most of the record's light, a bright
// disc where the record splats (textured Sibenik's marble floor). The diffuse base keeps all direct light, and the
// lobe keeps the environment's smooth part (one sample of the lobe that escapes), which the map does not shoot. Only
// the irradiance records' program defines CAUSTICS_APART (host/passes/record_pass.cpp); later bounces, the radiance
// records and the path tracer count every path themselves. The glossy pass's paths use it past a rough or Lambertian
// hit no record reaches, where they read the caustic map instead (kernels/glossy.cl glossy_path_step).
inline float3 hit_direct_without_caustics(SCENE_ARGS, HitSurface* h, float3 dir, float u, float v, float u_lobe,
                                          RayTally* rays) {
  if (hit_lobe_kind(materials, textures, texels, h) != LOBE_GLOSSY)
    return hit_direct(SCENE, h, dir, u, v, u_lobe, rays);
  BrdfInputs in = surface_brdf(hit_albedo(materials, textures, texels, h), hit_lobe(materials, textures, texels, h), h->ns);
  ShadingFrame frame = shading_frame(h->ns);
  float3 wo = view_local(frame, -dir);
  float3 e = direct_irradiance(BVH, lights, scene_counts.light_count, EMITTERS, scene_counts.emitter_count,
                               h->s.position, h->ns, h->ng, u, v, rays);
  float3 l = (float3)(0.0f);
#if HAS_GLASS_CAUSTICS
  e += caustic_levels_irradiance(GLASS_CAUSTIC_MAP, h->s.position, h->ng, 0.0f);  // the light glass volumes passed
#endif
#if HAS_ENVIRONMENT
  float2 smooth_u = environment_extra_randoms(u, v, 0u), peak_u = environment_extra_randoms(u, v, 1u);
  e += environment_irradiance(SCENE, h->s.position, h->ns, h->ng, smooth_u.x, smooth_u.y, peak_u.x, peak_u.y, rays);
  float2 lobe_u = environment_extra_randoms(u, v, 2u);
  float3 wi = lobes_sample(in, wo, environment_extra_randoms(u, v, 3u).x, lobe_u.x, lobe_u.y), toward = to_world(frame, wi);
  float3 origin = offset_ray_origin(h->s.position, h->ng);
  if (wi.z > 0.0f && dot(toward, h->ng) > 0.0f) {
    const float3 passes = escapes(BVH, origin, &toward, rays);
    if (any_positive(passes))
      l += lobes_weight(in, wo, wi) * environment_smooth(environment, scene_counts, toward) * passes;
  }
#endif
  return finite_or_zero(l + brdf_eval_diffuse(in, wo) * e);
}
#endif

// The bounces after the first (--bounces N: N - 1 of them): from each hit the path goes on along a direction drawn
// from the hit's BRDF (cosine-weighted where Lambertian), and each new hit adds its directly lit radiance times the
// path's throughput. Emission found on the way is never counted (direct light at each hit counts it). Random numbers:
// bounce k (1 ..) takes dimensions PATH_FIRST_DIMENSION + 6 (k - 1) .. + 5 of (key, sample).
#define PATH_FIRST_DIMENSION 8u
typedef struct {
  uint key, sample, bounces;
} PathContinuation;

// The continuation of sample `sample` (random stream `key`) for a frame of `bounces` bounces in all (0 counts as 1).
inline PathContinuation path_continuation(uint key, uint sample, uint bounces) {
  PathContinuation more = {key, sample, bounces > 1u ? bounces - 1u : 0u};
  return more;
}

// Bounce k of a continued path from *h (reached along *dir): draws the next direction from h's BRDF, multiplies
// *throughput by f cos / pdf and traces it; *next is the new hit, *dir the new direction. false: the path ends here
// (*h and *dir are then unchanged).
inline bool path_extend(SCENE_ARGS, HitSurface* h, float3* dir, float3* throughput, PathContinuation more, uint k,
                        HitSurface* next_hit, RayTally* rays) {
  uint d = PATH_FIRST_DIMENSION + 6u * k;
  float u1 = random01(more.key, more.sample, d), u2 = random01(more.key, more.sample, d + 1u);
  float3 next;
#if HAS_SPECULAR_BRDF
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  if (lobe.lobe != LOBE_NONE) {
    ShadingFrame frame = shading_frame(h->ns);
    float3 wi;
    float pdf;
    BrdfInputs brdf = surface_brdf(hit_albedo(materials, textures, texels, h), lobe, h->ns);
    *throughput *=
        brdf_sample(brdf, view_local(frame, -*dir), random01(more.key, more.sample, d + 2u), u1, u2, &wi, &pdf);
    next = to_world(frame, wi);
  } else
#endif
  {
    float3 t, b;
    tangent_frame(h->ns, &t, &b);
    next = cosine_direction(t, b, h->ns, u1, u2);
    *throughput *= hit_albedo(materials, textures, texels, h);  // cosine-weighted: f cos / pdf = albedo
  }
  if (!any_positive(*throughput) || dot(next, h->ng) <= 0.0f)
    return false;
  float distance;
  float3 through_glass;
  if (!trace_surface(SCENE, offset_ray_origin(h->s.position, h->ng), &next, 0.0f, next_hit, &distance, &through_glass,
                     rays))
    return false;
  *throughput *= through_glass;
  *dir = next;
  return true;
}

// The random numbers of bounce k's light sample at its new hit (path_step): light sample (u, v) and lobe.
inline float3 path_light_randoms(PathContinuation more, uint k) {
  uint d = PATH_FIRST_DIMENSION + 6u * k;
  return (float3)(random01(more.key, more.sample, d + 3u), random01(more.key, more.sample, d + 4u),
                  random01(more.key, more.sample, d + 5u));
}

// path_extend, then the new hit's direct light times the path's throughput added to *sum; *h moves on to that hit.
inline bool path_step(SCENE_ARGS, HitSurface* h, float3* dir, float3* throughput, PathContinuation more, uint k,
                      float3* sum, RayTally* rays) {
  HitSurface h_next;
  if (!path_extend(SCENE, h, dir, throughput, more, k, &h_next, rays)) return false;
  const float3 r = path_light_randoms(more, k);
  *sum += *throughput * hit_direct(SCENE, &h_next, *dir, r.x, r.y, r.z, rays);
  *h = h_next;
  return true;
}

#if PHOTON_GATHER
// The later bounces' light that *h (reached along dir) reflects back along -dir, from the photon map's two estimates
// at the nearest lookup photon (kernels/photon_map.h): R, the light its neighbours reflect (their albedo averaged in:
// no texel read here), and E, the irradiance, both over pi. Lambertian: R. With a specular lobe, the incident light
// taken as even over directions, as composition reflects a rough pixel's cached irradiance (kernels/compose.cl): the
// diffuse base (1 - metallic)(1 - E_d(n.v)) R plus the lobe's directional albedo c0 T0 + c1 T1 (kernels/brdf.h)
// times E, whose metallic part of c0 (base colour) and of c1 (1 - base) reads R and E - R. shallow: without the map's
// last landing. nearest: the lookup photon (supported_photon).
inline float3 photon_gather(SCENE_ARGS, PHOTON_MAP_ARGS, HitSurface* h, float3 dir, int nearest, bool shallow) {
  __global const float4* estimates = shallow ? map_shallow : map_radiance;
  float3 reflected = estimates[2 * nearest].xyz;
#if HAS_SPECULAR_BRDF
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  if (lobe.lobe != LOBE_NONE) {
    float3 irradiance = estimates[2 * nearest + 1].xyz;
#if HAS_LAYERS
    // Layers: the base's terms below under the layers' share toward the view, and the layers' own albedo times E (the
    // coat's Fresnel needs the view's direction about its normal: a shading frame).
    BrdfInputs in = surface_brdf((float3)(1.0f), lobe, h->ns);
    const float3 wo = view_local(shading_frame(h->ns), -dir);
    const float cos_o = has_layer_lobes(in) ? wo.z : fmax(dot(h->ns, -dir), 1e-4f);  // the latter: the bits without
    const float3 f0 = in.f0;
#else
    BrdfInputs in = brdf_inputs((float3)(1.0f), lobe.metallic, lobe.roughness, lobe.specular);
    // Only the view's angle matters (the lobe's albedo is isotropic): no shading frame; as view_local, a normal tilted
    // past the viewer is taken just above the horizon.
    float cos_o = fmax(dot(h->ns, -dir), 1e-4f);
    const float f0 = DIELECTRIC_F0;
#endif
    float2 terms = specular_albedo_split(in, cos_o);
    float dielectric = (1.0f - in.metallic) * in.specular;
    float3 c0 = dielectric * f0 * irradiance + in.metallic * reflected;
    float3 c1 = dielectric * (1.0f - f0) * irradiance + in.metallic * (irradiance - reflected);
    // The diffuse weight from the same terms: the table read once for both.
    const float3 base =
        (1.0f - in.metallic) * diffuse_weight_from_terms(in, terms) * reflected + terms.x * c0 + terms.y * c1;
#if HAS_LAYERS
    if (has_layer_lobes(in)) return layers_base_share(in, wo) * base + layers_own_albedo(in, wo) * irradiance;
#endif
    return base;
  }
#endif
  return reflected;
}
#endif

#if PHOTON_GATHER
// The lookup photon whose estimates stand for *h, or -1 where the map cannot support them: no lookup photon near, or
// one whose disc held fewer than map.min_support photons. Where few photons land (a room lit through a gap, behind a
// door), an estimate from a handful is noisy and biased (its fit is clamped, and a lookup that finds no photon reads
// black): the ray continues its path there instead, which costs rays only where the map is thin (docs/ALGORITHM.md
// section 8).
inline int supported_photon(PHOTON_MAP_ARGS, HitSurface* h) {
  int nearest = photon_map_nearest(PHOTON_MAP, h->s.position, h->ng);
  if (nearest < 0) return map.min_support > 0.0f ? -1 : -2;  // -2: none, and no fallback asked for (reads black)
  return map_radiance[2 * nearest].w >= map.min_support ? nearest : -1;
}
#endif

// What a ray along dir that hits nothing brings: the environment's smooth part (kernels/environment.h; the peak is
// the pixel's direct light), or nothing.
inline float3 miss_radiance(SCENE_ARGS, float3 dir) {
#if HAS_ENVIRONMENT
  return environment_smooth(environment, scene_counts, dir);
#else
  return (float3)(0.0f);
#endif
}

// What a path must still do after the light at its first hit (first_bounce_from_hit): nothing, go on bounce after
// bounce (path_bounce), or (PHOTON_GATHER, a short ray) take one step and read the map there. The wavefront trace
// queues the last two (kernels/path_queue.h).
#define PATH_DONE 0u
#define PATH_CONTINUES 1u
#define PATH_STEPS_THEN_GATHERS 2u

// The light a ray along dir brings back from *h, the surface it hit at distance `distance`, before any path goes on
// from there: h's directly lit radiance, and where the photon map stands for the later bounces, the map's estimate.
// (u, v) pick the light sample at h, u_lobe the lobe of its BRDF sample where h is glossy; *after says what the path
// must still do (PATH_DONE ..), its light added as finite_or_zero(sum).
inline float3 first_bounce_from_hit(SCENE_ARGS GATHER_MAP_ARGS, HitSurface* h, float3 dir, float distance, float u,
                                    float v, float u_lobe, PathContinuation more, RayTally* rays, uint* after) {
#if CAUSTICS_APART
  float3 l = hit_direct_without_caustics(SCENE, h, dir, u, v, u_lobe, rays);
#else
  float3 l = hit_direct(SCENE, h, dir, u, v, u_lobe, rays);
#endif
  *after = PATH_DONE;
  if (!more.bounces || !rays_answered(rays)) return l;  // a round that only lists its rays needs nothing more
#if PHOTON_GATHER
  // A short ray: the map's disc would span the record's own surroundings. The path goes one bounce further and reads
  // there the map without its last landing (bounces 3 .. N), or goes on where the map is thin.
  if (distance < map.short_path_distance) {
    *after = PATH_STEPS_THEN_GATHERS;
    return l;
  }
  int nearest = supported_photon(PHOTON_MAP, h);
  if (nearest >= 0) l += finite_or_zero(photon_gather(SCENE, PHOTON_MAP, h, dir, nearest, false));
  else if (nearest == -1) *after = PATH_CONTINUES;
#else
  *after = PATH_CONTINUES;
#endif
  return l;
}

// Bounce k of a path going on after its first hit (mode PATH_CONTINUES or PATH_STEPS_THEN_GATHERS): path_step, then
// for a short ray's first step the map without its last landing, or where the map is thin the path going on. false:
// the path ends here.
inline bool path_bounce(SCENE_ARGS GATHER_MAP_ARGS, HitSurface* h, float3* dir, float3* throughput,
                        PathContinuation more, uint k, uint mode, float3* sum, RayTally* rays) {
  if (!path_step(SCENE, h, dir, throughput, more, k, sum, rays)) return false;
#if PHOTON_GATHER
  if (mode == PATH_STEPS_THEN_GATHERS && k == 0u) {
    int nearest = supported_photon(PHOTON_MAP, h);
    if (nearest >= 0) {
      *sum += *throughput * photon_gather(SCENE, PHOTON_MAP, h, *dir, nearest, true);
      return false;
    }
    return nearest == -1;
  }
#endif
  return true;
}

// Radiance a ray along dir brings back from *h, the surface it hit at distance `distance`: the light h reflects after
// one reflection, and after more.bounces more (or what the photon map holds there); (u, v) pick the light sample at
// h, and u_lobe the lobe of its BRDF sample where h is glossy. The path's bounces run here in a loop; the wavefront
// record trace runs the same path_bounce calls one kernel a bounce, with the same bits.
inline float3 radiance_from_hit(SCENE_ARGS GATHER_MAP_ARGS, HitSurface* h, float3 dir, float distance, float u,
                                float v, float u_lobe, PathContinuation more, RayTally* rays) {
  uint after;
  float3 l = first_bounce_from_hit(SCENE GATHER_MAP, h, dir, distance, u, v, u_lobe, more, rays, &after);
  if (after != PATH_DONE) {
    float3 sum = (float3)(0.0f), throughput = (float3)(1.0f);
    for (uint k = 0u; k < more.bounces; ++k)
      if (!path_bounce(SCENE GATHER_MAP, h, &dir, &throughput, more, k, after, &sum, rays)) break;
    l += finite_or_zero(sum);
  }
  return l;
}

// Radiance arriving at origin from direction dir (radiance_from_hit, or miss_radiance); *distance is the hit
// distance, INFINITY on a miss.
inline float3 bounce_radiance(SCENE_ARGS GATHER_MAP_ARGS, float3 origin, float3 dir, float u, float v, float u_lobe,
                              PathContinuation more, float* distance, RayTally* rays) {
  HitSurface h;
  float3 through_glass;
  if (!trace_surface(SCENE, origin, &dir, 0.0f, &h, distance, &through_glass, rays))
    return miss_radiance(SCENE, dir) * through_glass;
  return radiance_from_hit(SCENE GATHER_MAP, &h, dir, *distance, u, v, u_lobe, more, rays) * through_glass;
}

#endif
