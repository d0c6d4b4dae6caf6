// The specular part of the indirect light at pixels whose lobe is glossy (LOBE_GLOSSY), by sampling the lobe:
// the cache's irradiance carries the diffuse base (kernels/splat.cl), and a glossy lobe is too narrow for irradiance
// to stand in for the light it reflects. Each sample reflects the view about a visible normal of the GGX lobe
// (Heitz 2018) and weighs the directly lit radiance its ray finds (kernels/bounce.h) by F G2 / G1; with a light guide,
// some samples aim at its clusters instead (below). The samples come in chunks, each an estimate of its own, and in
// rounds: every sampled sub-pixel takes one chunk, then the output pixels whose estimated error is largest take more
// (passes/glossy_pass.h chooses them). A round adds each sub-pixel's chunk estimates (RGB) and rays (A) to glossy_sums
// and its samples' luminance moments to glossy_moments; average_glossy_chunks then writes RGB = the mean, A = the rays.
// With SAMPLE_HSH_LOBES the radiance-cacheable lobes (LOBE_HSH) are sampled too, for cache methods that do not
// radiance-cache them; without it, and with a light guide, the LOBE_HSH pixels get the share of their light that their
// radiance records leave to the guide (guide_share), in the first round.
#include "bounce.h"
#include "shading_normal.h"
#include "brdf_frame.h"
#include "caustic_map.h"
#include "counter_random.h"
#include "light_guide.h"
#include "path_queue.h"
#include "pixel_rounds.h"
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
// Past a rough or Lambertian hit that no record reaches (off screen, hidden from the camera), a path reads the caustic
// map there and leaves the light a sharp lobe at its next hit reflects of the lights out of that hit's direct light
// (glossy_path_step): the path light -> sharp lobe -> that hit is the map's. Traced instead, it is a point light's
// highlight in the marble floor found by one path in thousands through a random direction from a stone wall: single
// pixels 1000x their neighbours on textured Sibenik's floor (docs/NOTES.md, "Fireflies").
#define CACHED_LIGHT_ARGS , WORLD_RECORD_ARGS, CAUSTIC_MAP_ARGS
#define CACHED_LIGHT , WORLD_RECORDS, CAUSTIC_MAP

inline float3 cached_reflection(SCENE_ARGS, HitSurface* h, float3 dir, float3 e) {
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  float3 albedo = hit_albedo(materials, textures, texels, h);
  if (lobe.lobe == LOBE_NONE) return albedo * RC_INV_PI * e;
  BrdfInputs in = surface_brdf(albedo, lobe, h->ns);
  float3 wo = view_local(shading_frame(h->ns), -dir);
  return brdf_eval_diffuse(in, wo) * e + lobes_albedo(in, wo) * RC_INV_PI * e;
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

// Path-space regularization (Kaplanyan and Dachsbacher 2013): at a sample's second hit and later, a sharp lobe
// (LOBE_GLOSSY) reflects the lights' direct light as a lobe of at least GLOSSY_REGULARIZED_ROUGHNESS would, spreading
// a highlight that only a chain of near-mirror reflections reaches (textured Sibenik's marble floor seen in its own
// marble steps, alpha 0.0038: one sample in thousands finds the point light's highlight there, and brings 1000x its
// pixel's light). The bias is a blur of those highlights; the mean it moves is measured in docs/NOTES.md
// ("Fireflies through chains of mirrors"). The first hit, which the pixel's own lobe aims at, stays exact.
#define GLOSSY_REGULARIZED_ROUGHNESS 0.3f
inline float3 hit_direct_regularized(SCENE_ARGS, HitSurface* h, float3 dir, float u, float v, float u_lobe,
                                     RayTally* rays) {
  if (hit_lobe_kind(materials, textures, texels, h) != LOBE_GLOSSY) return hit_direct(SCENE, h, dir, u, v, u_lobe, rays);
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  lobe.roughness = fmax(lobe.roughness, GLOSSY_REGULARIZED_ROUGHNESS);
#if HAS_LAYERS
  lobe.layers.clearcoat_roughness = fmax(lobe.layers.clearcoat_roughness, GLOSSY_REGULARIZED_ROUGHNESS);
#endif
  LazyBrdf brdf = built_brdf(surface_brdf(hit_albedo(materials, textures, texels, h), lobe, h->ns));
  return direct_reflected(SCENE, &brdf, LOBE_GLOSSY, h->s.position, h->ns, h->ng, -dir, u, v, u_lobe, rays);
}

// Bounce k of a sample's path from *h, a hit the records do not reach: path_step, with the next hit's direct light
// regularized (above); but where h is rough or Lambertian and the scene has a caustic map, h adds the map's
// irradiance reflected along -*dir, and the next hit's direct light leaves out what the map holds (kernels/bounce.h
// hit_direct_without_caustics).
inline bool glossy_path_step(SCENE_ARGS CACHED_LIGHT_ARGS, HitSurface* h, float3* dir, float3* throughput,
                             PathContinuation more, uint k, float3* sum, RayTally* rays) {
  const int lobe = hit_lobe_kind(materials, textures, texels, h);
  const bool map_holds_caustics = caustic_grid.photon_count > 0u && (lobe == LOBE_NONE || lobe == LOBE_ROUGH);
  if (map_holds_caustics)
    *sum += *throughput * cached_reflection(SCENE, h, *dir, caustic_irradiance(CAUSTIC_MAP, h->s.position, h->ng));
  HitSurface h_next;
  if (!path_extend(SCENE, h, dir, throughput, more, k, &h_next, rays)) return false;
  const float3 r = path_light_randoms(more, k);
  *sum += *throughput * (map_holds_caustics ? hit_direct_without_caustics(SCENE, &h_next, *dir, r.x, r.y, r.z, rays)
                                            : hit_direct_regularized(SCENE, &h_next, *dir, r.x, r.y, r.z, rays));
  *h = h_next;
  return true;
}

// The radiance a sample's ray along dir brings back: as bounce_radiance, but a path that lands where the records
// reach reads them there and ends.
inline float3 sample_radiance(SCENE_ARGS CACHED_LIGHT_ARGS, float3 origin, float3 dir, float u, float v, float u_lobe,
                              PathContinuation more, RayTally* rays) {
  HitSurface h;
  float distance;
  float3 through_glass;
  if (!trace_surface(SCENE, origin, &dir, SECONDARY_CONE_ANGLE, &h, &distance, &through_glass, rays))
    return miss_radiance(SCENE, dir) * through_glass;
  if (!world_grid.record_count)
    return radiance_from_hit(SCENE, &h, dir, distance, u, v, u_lobe, more, rays) * through_glass;
  float3 sum = hit_direct(SCENE, &h, dir, u, v, u_lobe, rays), throughput = (float3)(1.0f), cached;
  for (uint k = 0; k < more.bounces; ++k) {
    if (cached_light(SCENE CACHED_LIGHT, &h, dir, &cached)) {
      sum += throughput * cached;
      break;
    }
    if (!glossy_path_step(SCENE CACHED_LIGHT, &h, &dir, &throughput, more, k, &sum, rays)) break;
  }
  return finite_or_zero(sum * through_glass);
}

// Where a pixel's samples take their light (glossy_sub_pixel): GLOSSY_WHOLE traces each sample's path there and then (one
// kernel, glossy_indirect); the wavefront (GroupSizes::record_trace) runs the pixel twice around its samples' kernels:
// GLOSSY_AIM keeps each sample's direction in its slot, and GLOSSY_GATHER reads each sample's light back from it, in
// the same order and the same sums, so the pixel is the same bits. A slot: (direction, sample id + 1) for a ray to
// cast, then (light, rays cast) with the counts' bits in w; (0, 0) where the sample casts no ray.
#define GLOSSY_WHOLE 0u
#define GLOSSY_AIM 1u
#define GLOSSY_GATHER 2u

inline float3 glossy_sample_light(SCENE_ARGS CACHED_LIGHT_ARGS, uint phase, __global float4* slot, float3 origin,
                                  float3 dir, uint key, uint s, uint bounces, RayTally* rays) {
  if (phase == GLOSSY_AIM) {
    *slot = (float4)(dir, as_float(s + 1u));  // the sample's id, for the first hit's shading
    return (float3)(0.0f);
  }
  if (phase == GLOSSY_GATHER) {
    const float4 light = *slot;
    rays->cast += as_uint(light.w);
    return light.xyz;
  }
  return sample_radiance(SCENE CACHED_LIGHT, origin, dir, random01(key, s, 2u), random01(key, s, 3u),
                         random01(key, s, 4u), path_continuation(key, s, bounces), rays);
}

// A sub-pixel's random stream.
inline uint glossy_key(uint pixel, uint seed) { return hash_u32(pixel ^ hash_u32(seed ^ STREAM_GLOSSY)); }

inline uint round_output_pixel(GlossyParams params, __global const uint* pixel_list, uint i) {
  return listed_output_pixel(params.listed, pixel_list, i);
}
// The sub-pixel whose samples fill wavefront slot i of the round's launch from first_item.
inline uint slot_sub_pixel(__global const CameraParams* camera, GlossyParams params, __global const uint* pixel_list,
                           uint first_item, size_t i) {
  const uint subs = sub_pixels_per_pixel(camera), sub_pixel = (uint)(i / params.slots_per_sub_pixel);
  return sub_pixel_of(camera, round_output_pixel(params, pixel_list, first_item + sub_pixel / subs), sub_pixel % subs);
}

// Whether the pass samples a G-buffer sample's lobe (the pixels its rounds refine).
inline bool glossy_samples_lobe(GBufferSample g) {
  return g.triangle >= 0 && (g.lobe == LOBE_GLOSSY || (SAMPLE_HSH_LOBES && g.lobe == LOBE_HSH));
}

// A chunk's samples: GLOSSY_CHUNK_LOBE from the lobe (ids 2c, 2c + 1, points 2c s^2 + sub ... of the output pixel's
// nested strata, so an output pixel's first chunks fill its quadrants across its sub-pixels) and, where the lobe faces
// a cone of the guide, GLOSSY_CHUNK_GUIDED aimed into the cones (ids from GLOSSY_GUIDED_SAMPLE).
#define GLOSSY_GUIDED_SAMPLE 0x100000u
// A near-mirror lobe (GGX alpha below NEAR_MIRROR_ALPHA, roughness 0.1) sends every sample of a sub-pixel nearly the
// same way: its chunk is one lobe sample and no guided one (a guided direction it would not reflect). Textured
// Sibenik's marble floor (alpha 0.0038) is most of its glossy pixels.
#define NEAR_MIRROR_ALPHA 0.01f
inline uint glossy_chunk_lobe_samples(BrdfInputs in) { return in.alpha < NEAR_MIRROR_ALPHA ? 1u : GLOSSY_CHUNK_LOBE; }
inline uint glossy_slots_per_chunk(GlossyParams params) {
  return GLOSSY_CHUNK_LOBE + (params.guide_clusters ? GLOSSY_CHUNK_GUIDED : 0u);
}

// With a light guide (params.guide_clusters > 0), a pixel whose lobe faces one of its clusters (kernels/light_guide.h)
// adds half as many samples again, aimed into their cones (a chunk's guided sample), and both kinds are weighed by the
// balance heuristic within the chunk (Veach 1997): a small bright patch that the lobe's own samples find in one pixel of many (fireflies) is found by
// every pixel.
// Cones are chosen in proportion to their promised irradiance times the lobe toward them; a cone that the
// lobe's own samples would hit GUIDE_MAX_STRATA times or more (a wall beside a glossy floor) is left to them, as the
// records leave such cones to their strata.

inline uint glossy_guide_cones(__global const GuideCluster* guide, uint clusters, float3 p, ShadingFrame frame,
                               BrdfInputs in, float3 wo, float lobe_samples, GuideCone* cones) {
  if (!clusters) return 0u;
  uint count = guide_cones(guide, clusters, p, frame.n, 4.0f * RC_PI, cones);
  const float3 mirror = (float3)(-wo.x, -wo.y, wo.z);  // the lobe's peak, near enough
  for (uint c = 0; c < count; ++c) {
    float3 axis = to_local(frame, cones[c].axis);
    // Small: the lobe's own samples expected in the cone (the share of the lobe it holds, estimated at its axis, at
    // most 1) stay below GUIDE_MAX_STRATA.
    bool small = axis.z > 0.0f && lobe_samples * fmin(lobes_pdf(in, wo, axis) / cones[c].inv_solid_angle,
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
                          float3 p, float3 ng, float3 origin, ShadingFrame frame, BrdfInputs in, float3 wo, uint key,
                          uint phase, __global float4* slots, RayTally* rays) {
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
    if (!any_positive(f)) continue;
    float3 l = glossy_sample_light(SCENE CACHED_LIGHT, phase, slots + s, origin, dir, key, s, params.bounces, rays);
    if (phase == GLOSSY_AIM) continue;  // the direction is all the aim keeps
    float guide_density = guide_pdf_drawn(cones, cone_count, dir, drawn_from);
    sum += f * l * (wi.z * record_guided / (strata_density * wi.z + record_guided * guide_density));
  }
  return sum / (float)max(params.guide_share_samples, 1u);
}

// One round's samples of output pixel output_pixel's sub-pixel `sub` (GLOSSY_WHOLE, GLOSSY_GATHER: added to its sums
// and moments; the first round writes them, zero where the pass samples nothing), or their directions into its
// params.slots_per_sub_pixel slots (GLOSSY_AIM).
inline void glossy_sub_pixel(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, __global const GuideCluster* guide,
                             WORLD_RECORD_ARGS, CAUSTIC_MAP_ARGS, uint output_pixel, uint sub, uint phase,
                             __global float4* slots, __global float4* glossy_sums, __global float4* glossy_moments) {
  if (phase == GLOSSY_AIM)
    for (uint k = 0; k < params.slots_per_sub_pixel; ++k) slots[k] = (float4)(0.0f);
  const uint subs = sub_pixels_per_pixel(camera), pixel = sub_pixel_of(camera, output_pixel, sub);
  const bool first_round = params.first_chunk == 0u;
  GBufferSample g = gbuffer[pixel];
  const bool sampled = glossy_samples_lobe(g);
  const bool cached_with_guide = first_round && !SAMPLE_HSH_LOBES && g.triangle >= 0 && g.lobe == LOBE_HSH &&
                                 params.guide_share_samples > 0u && params.guide_clusters > 0u;
  if (!(sampled || cached_with_guide)) {
    if (phase != GLOSSY_AIM && first_round) glossy_sums[pixel] = glossy_moments[pixel] = (float4)(0.0f);
    return;
  }
  float3 p = vload3(0, g.position), ng = vload3(0, g.geometric_normal);
  ShadingFrame frame = shading_frame(gbuffer_shading_normal(g));
  BrdfInputs in = gbuffer_layered_brdf(g, pixel_layers(gbuffer_layers, pixel), frame.n);
  float3 wo = view_local(frame, camera_view_direction(camera, p));
  float3 origin = offset_ray_origin(p, ng);
  uint key = glossy_key(pixel, params.seed);
  RayTally rays = traced_rays(0u);
  if (cached_with_guide) {
    float3 share =
        guide_share(SCENE CACHED_LIGHT, guide, params, p, ng, origin, frame, in, wo, key, phase, slots, &rays);
    if (phase == GLOSSY_AIM) return;
    glossy_sums[pixel] = (float4)(finite_or_zero(share), (float)rays.cast);
    glossy_moments[pixel] = (float4)(0.0f, 0.0f, 0.0f, 1.0f);  // one estimate, outside the rounds' error
    return;
  }
  GuideCone cones[GUIDE_MAX_CONES];
  const uint chunk_end = params.first_chunk + params.round_chunks;
  // The guide leaves to the lobe the cones the pixel's lobe samples, after this round, would hit often.
  const uint cone_count = glossy_guide_cones(guide, params.guide_clusters, p, frame, in, wo,
                                             (float)(GLOSSY_CHUNK_LOBE * chunk_end), cones);
  const uint lobe_samples = glossy_chunk_lobe_samples(in);
  const uint guided = cone_count && lobe_samples == GLOSSY_CHUNK_LOBE ? GLOSSY_CHUNK_GUIDED : 0u;
  const uint per_chunk = glossy_slots_per_chunk(params);
  const uint strata_key = hash_u32(output_pixel ^ hash_u32(params.seed ^ STREAM_GLOSSY_STRATA));
  float3 sum = (float3)(0.0f);
  float sum_y = 0.0f, sum_y2 = 0.0f, samples = 0.0f;
  for (uint c = params.first_chunk; c < chunk_end; ++c) {
    float3 chunk = (float3)(0.0f);
    for (uint j = 0; j < GLOSSY_CHUNK_LOBE + guided; ++j) {
      if (j >= lobe_samples && j < GLOSSY_CHUNK_LOBE) continue;  // a near-mirror chunk's one sample
      const bool from_lobe = j < GLOSSY_CHUNK_LOBE;
      const uint s = from_lobe ? GLOSSY_CHUNK_LOBE * c + j : GLOSSY_GUIDED_SAMPLE + c;
      float u1 = random01(key, s, 0u), u2 = random01(key, s, 1u);
      float3 wi;
      uint drawn_from = GUIDE_MAX_CONES;  // a lobe sample: no cone
      if (from_lobe) {
        const float2 cell = nested_stratum_point(s * subs + sub, strata_key, u1, u2);
        wi = lobes_sample(in, wo, random01(key, s, 6u), cell.x, cell.y);
      } else {
        // Independent numbers, not the net of guide_share: on the corridor with metal walls of roughness 0.3 the net
        // took the median frame's relMSE 0.70x but gave 3 of 32 seeds a frame worse than any of the 32 before (one
        // 10x): a heavier tail, unexplained (RESULTS.md "Issue 13, twelfth step").
        wi = to_local(frame, sample_guide(cones, cone_count, random01(key, s, 5u), u1, u2, &drawn_from));
      }
      samples += 1.0f;  // a sample that casts no ray counts, as the zero it adds
      if (wi.z <= 0.0f) continue;
      float3 dir = to_world(frame, wi);
      if (dot(dir, ng) <= 0.0f) continue;
      float3 l = glossy_sample_light(SCENE CACHED_LIGHT, phase, slots + (c - params.first_chunk) * per_chunk + j,
                                     origin, dir, key, s, params.bounces, &rays);
      if (phase == GLOSSY_AIM) continue;  // the weights wait for the gather
      float3 y = (float3)(0.0f);
      if (!guided) {
        y = lobes_weight(in, wo, wi) * l;
      } else {
        // Balance heuristic within the chunk: f cos L / (n_lobe p_lobe + n_guide p_guide) for either kind.
        float lobe_density = (float)GLOSSY_CHUNK_LOBE * lobes_pdf(in, wo, wi);
        float combined = lobe_density + (float)guided * guide_pdf_drawn(cones, cone_count, dir, drawn_from);
        if (combined > 0.0f) y = brdf_eval_specular(in, wo, wi) * l * (wi.z * (float)GLOSSY_CHUNK_LOBE / combined);
      }
      y = finite_or_zero(y);
      chunk += y;
      const float y_luminance = luminance(y);
      sum_y += y_luminance;
      sum_y2 += y_luminance * y_luminance;
    }
    sum += chunk / (float)lobe_samples;
  }
  if (phase == GLOSSY_AIM) return;
  float4 sums = (float4)(sum, (float)rays.cast), moments = (float4)(sum_y, sum_y2, samples, (float)params.round_chunks);
  if (!first_round) {
    sums += glossy_sums[pixel];
    moments += glossy_moments[pixel];
  }
  glossy_sums[pixel] = sums;
  glossy_moments[pixel] = moments;
}

// A round's sub-pixels (item_count output pixels, each of its s^2 sub-pixels a work-item) traced and shaded whole...
__kernel void glossy_indirect(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, __global const GuideCluster* guide,
                              WORLD_RECORD_ARGS, CAUSTIC_MAP_ARGS, __global const uint* pixel_list, uint item_count,
                              __global float4* glossy_sums, __global float4* glossy_moments) {
  const uint i = get_global_id(0), subs = sub_pixels_per_pixel(camera);
  if (i < item_count * subs)
    glossy_sub_pixel(SCENE, GBUFFER, params, guide, WORLD_RECORDS, CAUSTIC_MAP,
                     round_output_pixel(params, pixel_list, i / subs), i % subs, GLOSSY_WHOLE, glossy_sums,
                     glossy_sums, glossy_moments);
}

// ... or as a wavefront (GroupSizes::record_trace), over launches of item_count output pixels from first_item, each
// sub-pixel with params.slots_per_sub_pixel sample slots: aim_glossy_samples keeps the samples' directions...
__kernel void aim_glossy_samples(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, __global const GuideCluster* guide,
                                 WORLD_RECORD_ARGS, CAUSTIC_MAP_ARGS, __global const uint* pixel_list, uint first_item,
                                 uint item_count, __global float4* sample_slots) {
  const uint i = get_global_id(0), subs = sub_pixels_per_pixel(camera);
  if (i < item_count * subs)
    glossy_sub_pixel(SCENE, GBUFFER, params, guide, WORLD_RECORDS, CAUSTIC_MAP,
                     round_output_pixel(params, pixel_list, first_item + i / subs), i % subs, GLOSSY_AIM,
                     sample_slots + (size_t)i * params.slots_per_sub_pixel, sample_slots, sample_slots);
}

// The slots of a launch of item_count output pixels.
inline size_t glossy_launch_slots(__global const CameraParams* camera, GlossyParams params, uint item_count) {
  return (size_t)item_count * sub_pixels_per_pixel(camera) * params.slots_per_sub_pixel;
}

// ... trace_glossy_samples traces them to their closest hits (prim -2: no ray)...
__kernel void trace_glossy_samples(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, __global const uint* pixel_list,
                                   uint first_item, uint item_count, __global const float4* sample_slots,
                                   __global HitDesc* hits) {
  size_t i = get_global_id(0);
  if (i >= glossy_launch_slots(camera, params, item_count)) return;
  const float4 slot = sample_slots[i];
  TraceHit hit = {INFINITY, 0.0f, 0.0f, -2};
  if (as_uint(slot.w)) {
    GBufferSample g = gbuffer[slot_sub_pixel(camera, params, pixel_list, first_item, i)];
    RayPrecomp r = ray_precompute(offset_ray_origin(vload3(0, g.position), vload3(0, g.geometric_normal)), slot.xyz);
    if (!bvh_trace(BVH, &r, 0.0f, INFINITY, false, &hit)) hit.prim = -1;
  }
  HitDesc out = {hit.t, hit.u, hit.v, hit.prim};
  hits[i] = out;
}

// ... shade_glossy_first_hits shades each hit as far as its first bounce's light (sample_radiance's first steps), and
// queues the paths that go on (kernels/path_queue.h)...
__kernel void shade_glossy_first_hits(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, WORLD_RECORD_ARGS,
                                      CAUSTIC_MAP_ARGS, __global const uint* pixel_list, uint first_item,
                                      uint item_count, __global float4* sample_slots, __global const HitDesc* hits,
                                      __global QueuedPath* paths, volatile __global uint* path_count,
                                      RAY_QUEUE_ARGS) {
  size_t i = get_global_id(0);
  if (i >= glossy_launch_slots(camera, params, item_count)) return;
  HitDesc hit = hits[i];
  if (hit.prim == -2) return;
  const float4 slot = sample_slots[i];
  float3 dir = slot.xyz;
  const uint s = as_uint(slot.w) - 1u;
  const uint key = glossy_key(slot_sub_pixel(camera, params, pixel_list, first_item, i), params.seed);
  const PathContinuation more = path_continuation(key, s, params.bounces);
  RayTally rays = queued_rays(RAY_QUEUE, i, 1u);
  uint after = PATH_DONE;
  float3 l, through_glass = (float3)(1.0f);
#if HAS_TRANSMISSION
  if (hit.prim >= 0) through_glass = kept_hit_past_glass(BVH, &rays, &hit, &dir);  // as trace_surface goes
#endif
  if (hit.prim < 0) {
    l = miss_radiance(SCENE, dir) * through_glass;
  } else {
    HitSurface h = hit_surface(HIT_SURFACE, hit.prim, hit.u, hit.v, dir, hit.t * SECONDARY_CONE_ANGLE);
    const float u = random01(key, s, 2u), v = random01(key, s, 3u), u_lobe = random01(key, s, 4u);
    if (!world_grid.record_count) {
      l = first_bounce_from_hit(SCENE, &h, dir, hit.t, u, v, u_lobe, more, &rays, &after) * through_glass;
    } else {
      l = hit_direct(SCENE, &h, dir, u, v, u_lobe, &rays) * through_glass;
      if (more.bounces) after = PATH_READS_RECORDS;
      else l = finite_or_zero(l);
    }
  }
  if (!rays_answered(&rays)) return;
  sample_slots[i] = (float4)(l, as_float(rays.cast));
  if (after != PATH_DONE)
    queue_path(paths, path_count, (uint)i, (uint)i, more, after, hit, dir,
               after == PATH_READS_RECORDS ? l : (float3)(0.0f), through_glass, 1.0f, rays.cast);
}

// Bounce k of a glossy sample's path: where it reads the records (PATH_READS_RECORDS), the records' light where they
// reach its hit, else a step on; otherwise as a record ray's path.
inline bool glossy_path_bounce(SCENE_ARGS CACHED_LIGHT_ARGS, HitSurface* h, float3* dir, float3* throughput,
                               PathContinuation more, uint k, uint mode, float3* sum, RayTally* rays) {
  if (mode != PATH_READS_RECORDS) return path_bounce(SCENE, h, dir, throughput, more, k, mode, sum, rays);
  float3 cached;
  if (cached_light(SCENE CACHED_LIGHT, h, *dir, &cached)) {
    *sum += *throughput * cached;
    return false;
  }
  return glossy_path_step(SCENE CACHED_LIGHT, h, dir, throughput, more, k, sum, rays);
}

// ... step_glossy_paths takes every queued path bounce `bounce` further (0 .. later_bounces - 1, a launch each)...
__kernel void step_glossy_paths(SCENE_ARGS, WORLD_RECORD_ARGS, CAUSTIC_MAP_ARGS, __global QueuedPath* paths,
                                __global const uint* path_count, uint bounce, uint later_bounces, RAY_QUEUE_ARGS) {
  const size_t i = get_global_id(0);
  HitSurface h;
  float3 dir, throughput, sum;
  PathContinuation more;
  RayTally rays = queued_rays(RAY_QUEUE, i, 0u);
  if (i >= *path_count ||
      !load_queued_path(HIT_SURFACE, paths + i, later_bounces, &h, &dir, &throughput, &sum, &more, &rays.cast))
    return;
  bool goes_on =
      glossy_path_bounce(SCENE CACHED_LIGHT, &h, &dir, &throughput, more, bounce, paths[i].mode, &sum, &rays);
  if (rays_answered(&rays))
    store_queued_path(paths + i, bounce, later_bounces, goes_on, &h, dir, throughput, sum, rays.cast);
}

// ... finish_glossy_paths writes each path's whole light into its slot...
__kernel void finish_glossy_paths(__global const QueuedPath* paths, __global const uint* path_count,
                                  __global float4* sample_slots) {
  const size_t i = get_global_id(0);
  if (i >= *path_count) return;
  __global const QueuedPath* path = paths + i;
  sample_slots[path->sample] = (float4)(queued_path_light(path, sample_slots[path->sample].xyz), as_float(path->rays));
}

// ... and gather_glossy_samples sums each sub-pixel's samples as glossy_indirect does.
__kernel void gather_glossy_samples(SCENE_ARGS, GBUFFER_ARGS, GlossyParams params, __global const GuideCluster* guide,
                                    WORLD_RECORD_ARGS, CAUSTIC_MAP_ARGS, __global const uint* pixel_list,
                                    uint first_item, uint item_count, __global float4* sample_slots,
                                    __global float4* glossy_sums, __global float4* glossy_moments) {
  const uint i = get_global_id(0), subs = sub_pixels_per_pixel(camera);
  if (i < item_count * subs)
    glossy_sub_pixel(SCENE, GBUFFER, params, guide, WORLD_RECORDS, CAUSTIC_MAP,
                     round_output_pixel(params, pixel_list, first_item + i / subs), i % subs, GLOSSY_GATHER,
                     sample_slots + (size_t)i * params.slots_per_sub_pixel, glossy_sums, glossy_moments);
}

// After the first round: each output pixel's error estimate, for the host to choose the pixels later rounds refine
// (passes/sample_rounds.h): (the variance of its glossy light's luminance, as its sub-pixels' samples estimate it, each
// sub-pixel's m samples in n chunks of k lobe samples taken as independent, Var(y) pooled over the pixel's sub-pixels:
// m Var(y) / (kn)^2, averaged over the s^2 sub-pixels; the
// luminance of its other light, emitted, direct and cached (from `direct` and `irradiance` where frame_light is 1); the
// sub-pixels the rounds refine; the luminance of its glossy light).
__kernel void glossy_pixel_error(GBUFFER_ARGS, __global const float4* irradiance, __global const float4* direct,
                                 uint frame_light, __global const float4* glossy_sums,
                                 __global const float4* glossy_moments, uint output_pixels,
                                 __global float4* error_out) {
  const uint o = get_global_id(0);
  if (o >= output_pixels) return;
  const uint subs = sub_pixels_per_pixel(camera);
  PooledMoments pool = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  float other = 0.0f, glossy = 0.0f;
  for (uint sub = 0; sub < subs; ++sub) {
    const uint pixel = sub_pixel_of(camera, o, sub);
    const GBufferSample g = gbuffer[pixel];
    const float4 moments = glossy_moments[pixel];
    if (moments.w > 0.0f) glossy += luminance(glossy_sums[pixel].xyz / moments.w);
    float3 light = vload3(0, g.emission);
    if (frame_light && g.triangle >= 0) {
      const float3 e = irradiance[pixel].xyz;
      light += direct[pixel].xyz;
      if (g.lobe == LOBE_NONE) {
        light += vload3(0, g.albedo) * RC_INV_PI * e;
      } else {
        const float3 wo = view_local(shading_frame(gbuffer_shading_normal(g)),
                                     camera_view_direction(camera, vload3(0, g.position)));
        light += brdf_eval_diffuse(gbuffer_layered_brdf(g, pixel_layers(gbuffer_layers, pixel),
                                                    gbuffer_shading_normal(g)), wo) * e;
      }
    }
    other += luminance(finite_or_zero(light));
    // A sub-pixel's n chunks of k lobe samples: an estimate of kn samples' mean.
    if (glossy_samples_lobe(g) && moments.z >= 1.0f)
      pool_sub_pixel(&pool, moments, moments.w * (float)glossy_chunk_lobe_samples(gbuffer_brdf(g)));
  }
  error_out[o] = pixel_error_estimate(pool, subs, other, glossy);
}

// Each sub-pixel's glossy light, the mean of its chunks (RGB), and the rays its samples cast (A).
__kernel void average_glossy_chunks(__global const float4* glossy_sums, __global const float4* glossy_moments,
                                    uint pixel_count, __global float4* glossy_out) {
  const uint i = get_global_id(0);
  if (i >= pixel_count) return;
  const float4 sums = glossy_sums[i];
  const float chunks = glossy_moments[i].w;
  glossy_out[i] = (float4)(chunks > 0.0f ? sums.xyz / chunks : (float3)(0.0f), sums.w);
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
