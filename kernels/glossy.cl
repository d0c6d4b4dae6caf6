// The specular part of the indirect light at pixels whose lobe is glossy (LOBE_GLOSSY), by sampling the lobe:
// the cache's irradiance carries the diffuse base (kernels/splat.cl), and a glossy lobe is too narrow for irradiance
// to stand in for the light it reflects. Each sample reflects the view about a visible normal of the GGX lobe
// (Heitz 2018), drawn from a grid_side x grid_side grid, and weighs the directly lit radiance its ray finds
// (kernels/bounce.h) by F G2 / G1; with a light guide, some samples aim at its clusters instead (below). Writes
// RGB = the mean, A = the rays the pixel cast. With SAMPLE_HSH_LOBES the radiance-cacheable lobes (LOBE_HSH) are
// sampled too, for cache methods that do not radiance-cache them; without it, and with a light guide, the LOBE_HSH
// pixels get the share of their light that their radiance records leave to the guide (guide_share).
#include "bounce.h"
#include "brdf_frame.h"
#include "counter_random.h"
#include "light_guide.h"
#include "world_records.h"

// A sample's path ends at its first hit on a Lambertian or rough surface that a record of the splat reaches
// (world_records.h): the bounces after that hit are read from the records (their irradiance, with the caustic map's
// at each record added by the host where the records leave caustics to it), reflected toward the path as composition
// reflects a pixel's
// (kernels/compose.cl). Elsewhere (a sharper lobe, a surface no record reaches: off screen, hidden from the camera)
// the path goes on as before and asks again at its next hit. What it trades (docs/ALGORITHM.md section 8): the
// records' interpolation error, seen blurred through the lobe, for the paths' noise; and a path read at its hit k
// (0: the first) gathers k + 1 bounces more than the `bounces` it would have, the records' own (they carry `bounces`
// after their point), which only brings it nearer the light of every bounce.
#define CACHED_LIGHT_ARGS , WORLD_RECORD_ARGS
#define CACHED_LIGHT , WORLD_RECORDS

inline float3 cached_reflection(SCENE_ARGS, HitSurface* h, float3 dir, float3 e) {
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  float3 albedo = hit_albedo(materials, textures, texels, h);
  if (lobe.lobe == LOBE_NONE) return albedo * RC_INV_PI * e;
  BrdfInputs in = surface_brdf(albedo, lobe);
  float3 wo = view_local(shading_frame(h->ns), -dir);
  return brdf_eval_diffuse(in, wo.z) * e + specular_albedo(in, wo) * RC_INV_PI * e;
}

// Whether the records reach *h (a Lambertian or rough surface, reached along dir): if so, *l is the light of the
// bounces after it that h reflects back along -dir.
inline bool cached_light(SCENE_ARGS CACHED_LIGHT_ARGS, HitSurface* h, float3 dir, float3* l) {
  int lobe = hit_lobe_kind(materials, textures, texels, h);
  if (lobe != LOBE_NONE && lobe != LOBE_ROUGH) return false;
  float weight;
  float3 e = world_cached_irradiance(WORLD_RECORDS, h->s.position, h->ns, &weight);
  if (!(weight > 0.0f)) return false;
  *l = cached_reflection(SCENE, h, dir, e);
  return true;
}

// The radiance a sample's ray along dir brings back: as bounce_radiance, but a path that lands where the records
// reach reads them there and ends.
inline float3 sample_radiance(SCENE_ARGS CACHED_LIGHT_ARGS, float3 origin, float3 dir, float u, float v, float u_lobe,
                              PathContinuation more, uint* rays) {
  HitSurface h;
  float distance;
  if (!trace_surface(SCENE, origin, dir, &h, &distance, rays)) return miss_radiance(SCENE, dir);
  if (!world_grid.record_count) return radiance_from_hit(SCENE, &h, dir, distance, u, v, u_lobe, more, rays);
  float3 sum = hit_direct(SCENE, &h, dir, u, v, u_lobe, rays), throughput = (float3)(1.0f), cached;
  for (uint k = 0; k < more.bounces; ++k) {
    if (cached_light(SCENE CACHED_LIGHT, &h, dir, &cached)) {
      sum += throughput * cached;
      break;
    }
    if (!path_step(SCENE, &h, &dir, &throughput, more, k, &sum, rays)) break;
  }
  return finite_or_zero(sum);
}

// With a light guide (params.guide_clusters > 0), a pixel whose lobe faces one of its clusters (kernels/light_guide.h)
// adds half as many samples again, aimed into their cones, and both kinds are weighed by the balance heuristic
// (Veach 1997): a small bright patch that the lobe's own samples find in one pixel of many (fireflies) is found by
// every pixel.
// Cones are chosen in proportion to their promised irradiance times the lobe toward them; a cone that the
// lobe's own samples would hit GUIDE_MAX_STRATA times or more (a wall beside a glossy floor) is left to them, as the
// records leave such cones to their strata.

// The density (solid angle) of reflecting wo about a visible normal of the lobe: D(h) G1(wo) / (4 wo.z).
inline float visible_normal_pdf(BrdfInputs in, float3 wo, float3 wi) {
  float a2 = in.alpha * in.alpha;
  return ggx_d(normalize(wo + wi), a2) * ggx_g1(wo.z, a2) / (4.0f * wo.z);
}

inline uint glossy_guide_cones(__global const GuideCluster* guide, uint clusters, float3 p, ShadingFrame frame,
                               BrdfInputs in, float3 wo, float lobe_samples, GuideCone* cones) {
  if (!clusters) return 0u;
  uint count = guide_cones(guide, clusters, p, frame.n, 4.0f * RC_PI, cones);
  const float3 mirror = (float3)(-wo.x, -wo.y, wo.z);  // the lobe's peak, near enough
  for (uint c = 0; c < count; ++c) {
    float3 axis = to_local(frame, cones[c].axis);
    // Small: the lobe's own samples expected in the cone (the share of the lobe it holds, estimated at its axis, at
    // most 1) stay below GUIDE_MAX_STRATA.
    bool small = axis.z > 0.0f && lobe_samples * fmin(visible_normal_pdf(in, wo, axis) / cones[c].inv_solid_angle,
                                                      1.0f) < GUIDE_MAX_STRATA;
    // The lobe at the cone's direction nearest its peak: a narrow lobe that meets only the cone's rim still counts.
    float cos_to_mirror = dot(mirror, axis), cos_max = cones[c].cos_max;
    float3 toward = mirror - cos_to_mirror * axis;
    float3 nearest = cos_to_mirror >= cos_max || !(dot(toward, toward) > 0.0f)
                         ? mirror
                         : cos_max * axis + sqrt(fmax(1.0f - cos_max * cos_max, 0.0f)) * normalize(toward);
    cones[c].promise *= small && nearest.z > 0.0f ? luminance(brdf_eval_specular(in, wo, nearest)) * nearest.z : 0.0f;
  }
  return guide_selection_cdf(cones, count);
}

// The share of a radiance-cached pixel's glossy light that its records leave to the light guide. A radiance record
// (kernels/records.cl with STORE_STRATA) caches L n_c p_c / (n_c p_c + n_g p_g) in HSH: its strata's balance-
// heuristic share beside n_g guided rays it does not cast. The pixel draws guide_share_samples directions from the
// same cones (the same clusters, selection and limits, seen from the pixel) and weighs each f cos L / p_g by the rest,
// n_g p_g / (n_c p_c + n_g p_g). So the light of a small bright patch is never truncated to the HSH order: through the
// basis it rang (dark bands beside its reflection) on glossy walls. Directions the lobe does not reflect cast no ray.
inline float3 guide_share(SCENE_ARGS CACHED_LIGHT_ARGS, __global const GuideCluster* guide, GlossyParams params,
                          float3 p, float3 ng,
                          float3 origin, ShadingFrame frame, BrdfInputs in, float3 wo, uint key, uint* rays) {
  const float strata_density = (float)params.record_strata * RC_INV_PI;  // n_c p_c / cos(theta)
  GuideCone cones[GUIDE_MAX_CONES];
  const uint cone_count =
      guide_cones(guide, params.guide_clusters, p, frame.n, GUIDE_MAX_STRATA / strata_density, cones);
  const float record_guided = (float)params.record_guide_rays;
  float3 sum = (float3)(0.0f);
  for (uint s = 0; s < (cone_count ? params.guide_share_samples : 0u); ++s) {
    uint drawn_from;
    float u, v, w;
    scrambled_sobol3(s, key, &u, &v, &w);  // a net, as a record's guided rays (kernels/records.cl guided_ray)
    float3 dir = sample_guide(cones, cone_count, u, v, w, &drawn_from);
    float3 wi = to_local(frame, dir);
    if (wi.z <= 0.0f || dot(dir, ng) <= 0.0f) continue;
    float3 f = brdf_eval_specular(in, wo, wi);
    if (!(f.x > 0.0f || f.y > 0.0f || f.z > 0.0f)) continue;
    float guide_density = guide_pdf_drawn(cones, cone_count, dir, drawn_from);
    float3 l = sample_radiance(SCENE CACHED_LIGHT, origin, dir, random01(key, s, 2u), random01(key, s, 3u),
                               random01(key, s, 4u), path_continuation(key, s, params.bounces), rays);
    sum += f * l * (wi.z * record_guided / (strata_density * wi.z + record_guided * guide_density));
  }
  return sum / (float)max(params.guide_share_samples, 1u);
}

__kernel void glossy_indirect(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, __global const GuideCluster* guide,
                              WORLD_RECORD_ARGS, __global float4* glossy_out) {
  uint pixel = get_global_id(0);
  if (pixel >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[pixel];
  bool sampled = g.lobe == LOBE_GLOSSY;
#if SAMPLE_HSH_LOBES
  sampled = sampled || g.lobe == LOBE_HSH;
#endif
  bool cached_with_guide = !SAMPLE_HSH_LOBES && g.lobe == LOBE_HSH && params.guide_share_samples > 0u &&
                           params.guide_clusters > 0u;
  if (g.triangle < 0 || !(sampled || cached_with_guide)) {
    glossy_out[pixel] = (float4)(0.0f);
    return;
  }
  float3 p = vload3(0, g.position), ng = vload3(0, g.geometric_normal);
  ShadingFrame frame = shading_frame(vload3(0, g.normal));
  BrdfInputs in = gbuffer_brdf(g);
  float3 wo = view_local(frame, camera_view_direction(camera, p));
  float3 origin = offset_ray_origin(p, ng);
  uint key = hash_u32(pixel ^ hash_u32(params.seed ^ STREAM_GLOSSY));
  if (cached_with_guide) {
    uint rays = 0;
    float3 share = guide_share(SCENE CACHED_LIGHT, guide, params, p, ng, origin, frame, in, wo, key, &rays);
    glossy_out[pixel] = (float4)(finite_or_zero(share), (float)rays);
    return;
  }
  GuideCone cones[GUIDE_MAX_CONES];
  const uint lobe_samples = params.sample_count, side = params.grid_side;
  const uint cone_count = glossy_guide_cones(guide, params.guide_clusters, p, frame, in, wo, (float)lobe_samples, cones);
  const uint guided = cone_count ? (lobe_samples + 1) / 2 : 0u, count = lobe_samples + guided;
  float3 sum = (float3)(0.0f);
  uint rays = 0;
  for (uint s = 0; s < count; ++s) {
    float u1 = random01(key, s, 0u), u2 = random01(key, s, 1u);
    bool from_lobe = s < lobe_samples;
    float3 wi;
    uint drawn_from = GUIDE_MAX_CONES;  // a lobe sample: no cone
    if (from_lobe) {
      if (s < side * side) {
        u1 = ((float)(s % side) + u1) / (float)side;
        u2 = ((float)(s / side) + u2) / (float)side;
      }
      wi = ggx_sample_reflection(wo, in.alpha, u1, u2);
    } else {
      // Independent numbers, not the net of guide_share: on the corridor with metal walls of roughness 0.3 the net
      // took the median frame's relMSE 0.70x but gave 3 of 32 seeds a frame worse than any of the 32 before (one
      // 10x): a heavier tail, unexplained (RESULTS.md "Issue 13, twelfth step").
      wi = to_local(frame, sample_guide(cones, cone_count, random01(key, s, 5u), u1, u2, &drawn_from));
    }
    if (wi.z <= 0.0f) continue;
    float3 dir = to_world(frame, wi);
    if (dot(dir, ng) <= 0.0f) continue;
    float3 l = sample_radiance(SCENE CACHED_LIGHT, origin, dir, random01(key, s, 2u), random01(key, s, 3u),
                               random01(key, s, 4u), path_continuation(key, s, params.bounces), &rays);
    if (!cone_count) {
      sum += brdf_specular_weight(in, wo, wi) * l;
      continue;
    }
    // Balance heuristic: f cos L / (n_lobe p_lobe + n_guide p_guide) for a sample of either kind.
    float lobe_density = (float)lobe_samples * visible_normal_pdf(in, wo, wi);
    float combined = lobe_density + (float)guided * guide_pdf_drawn(cones, cone_count, dir, drawn_from);
    if (combined > 0.0f) sum += brdf_eval_specular(in, wo, wi) * l * (wi.z * (float)lobe_samples / combined);
  }
  glossy_out[pixel] = (float4)(finite_or_zero(sum / (float)max(lobe_samples, 1u)), (float)rays);
}

// world_cached_irradiance at query points (xyz) with their shading normals, for tests: (E, sum of weights).
__kernel void cached_irradiance_at(WORLD_RECORD_ARGS, __global const float4* points, __global const float4* normals,
                                   uint point_count, __global float4* irradiance) {
  uint i = get_global_id(0);
  if (i >= point_count) return;
  float weight;
  float3 e = world_cached_irradiance(WORLD_RECORDS, points[i].xyz, normals[i].xyz, &weight);
  irradiance[i] = (float4)(e, weight);
}
