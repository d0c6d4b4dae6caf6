// Glass: glTF's KHR_materials_transmission with KHR_materials_ior and KHR_materials_volume (docs/ALGORITHM.md
// section 12). Where a material transmits, glTF's dielectric base is mix(diffuse, specular BTDF, transmission) under
// the Fresnel-weighted specular layer; a point is glass with probability transmission x (1 - metallic) (hashed by
// where it is, as blended alpha: every ray agrees on it, and the mixture's mean is glTF's for a dielectric), and opaque
// with its BRDF otherwise. A glass point is smooth: it reflects R = specular x F(cos, ior) (unpolarised Fresnel, total
// internal reflection included) and passes 1 - R tinted by its base colour. Thin-walled glass (no volume) passes rays
// straight; glass with a volume refracts them into and out of the mesh, which attenuates them by Beer-Lambert.
// Glass is never a surface the cache shades: camera rays look through it (glass_camera_ray), every other ray reflects
// or passes at random by R and goes on (pass_glass), and shadow rays pass it with its colour (light_transmittance).
#ifndef RCSPLAT_GLASS_H
#define RCSPLAT_GLASS_H
#include "counter_random.h"
#include "ray_queue.h"
#include "sampling.h"
#include "surface.h"

// Crossings a ray follows through glass before it is taken as absorbed (a ray trapped between two panes, or by total
// internal reflection).
#define GLASS_MAX_CROSSINGS 8u

#if HAS_TRANSMISSION
// Where a ray along dir leaves glass point s from: just off its surface on the side dir goes to.
inline float3 leaving_origin(SurfacePoint* s, float3 dir) {
  const float3 ng = s->geometric_normal;
  return offset_ray_origin(s->position, dot(dir, ng) > 0.0f ? ng : -ng);
}

// The share of a point that is glass: transmission (times its texture's R) times 1 - metallic.
inline float glass_share(__global const Material* m, __global const TextureInfo* textures, __global const uint* texels,
                         float2 uv) {
  float t = m->transmission;
#if HAS_TEXTURES
  if (t > 0.0f && m->transmission_texture >= 0)
    t *= sample_level(texels, textures[m->transmission_texture], uv, false).x;
#endif
  return t * (1.0f - m->metallic);
}

// Whether (prim, u, v) is glass: where its share is below 1, by a hash of where it is (its own stream, apart from
// blended alpha's).
inline bool is_glass(__global const TriangleShading* triangles, __global const Material* materials,
                     __global const TextureInfo* textures, __global const uint* texels, int prim, float u, float v) {
  __global const TriangleShading* t = triangles + prim;
  __global const Material* m = materials + t->material;
  if (!(m->transmission > 0.0f)) return false;
  const float w = 1.0f - u - v;
  const float share = glass_share(m, textures, texels, w * vload2(0, t->uv0) + u * vload2(0, t->uv1) + v * vload2(0, t->uv2));
  if (share >= 1.0f) return true;
  return random01((uint)prim ^ 0x676c6173u, as_uint(u), as_uint(v)) < share;  // "glas"
}

// Unpolarised Fresnel reflectance of a smooth interface seen at cos_i (> 0) from the side whose index is 1, the other
// side's being eta; *cos_t is the transmitted ray's cosine (0 on total internal reflection, where it returns 1).
inline float dielectric_reflectance(float cos_i, float eta, float* cos_t) {
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) {
    *cos_t = 0.0f;
    return 1.0f;
  }
  const float ct = sqrt(1.0f - sin2_t);
  const float rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  *cos_t = ct;
  return 0.5f * (rs * rs + rp * rp);
}

// One crossing of a glass point s, reached along unit dir at distance t from the ray's last point: returns the
// reflectance R; *through is the direction a passing ray takes and *tint what it keeps of the light besides 1 - R (the
// base colour, and leaving a volume its attenuation over t); *mirror the reflected direction. The side is the
// triangle's winding: a ray against the geometric normal enters the volume. `straight` (shadow rays, which pass a
// volume unbent): each face is taken as a refracting ray would meet it, entering at the angle the straight ray makes
// and leaving at the same angle (exactly so through a slab of parallel faces), so neither face reflects all the light
// by total internal reflection, and the attenuation runs over the refracted chord, t cos_i / cos_t.
inline float glass_crossing(__global const Material* materials, __global const TextureInfo* textures,
                            __global const uint* texels, SurfacePoint* s, float3 dir, float t, bool straight,
                            float3* through, float3* mirror, float3* tint) {
  __global const Material* m = materials + s->material;
  const bool entering = dot(s->geometric_normal, dir) < 0.0f;
  float3 n = entering ? s->shading_normal : -s->shading_normal;  // toward the side the ray comes from
  if (dot(n, dir) >= 0.0f) n = entering ? s->geometric_normal : -s->geometric_normal;
  const float cos_i = -dot(n, dir);
  const bool volume = m->thickness > 0.0f;
  const float eta = volume && !entering && !straight ? 1.0f / m->ior : m->ior;
  float cos_t;
  const float r = clamp(m->specular, 0.0f, 1.0f) * dielectric_reflectance(cos_i, eta, &cos_t);
  *mirror = dir + (2.0f * cos_i) * n;
  // Thin-walled glass lets the ray through unbent; a volume bends it by Snell's law (Fresnel's cos_t is its cosine).
  *through = volume && !straight ? normalize(dir / eta + (cos_i / eta - cos_t) * n) : dir;
  *tint = surface_albedo(materials, textures, texels, s);
  if (volume && !entering) *tint *= exp(-vload3(0, m->attenuation) * (straight ? t * cos_i / cos_t : t));
  return cos_t > 0.0f || !volume ? r : 1.0f;
}

// Crossing k of a chain at glass point s, reached at hit (its distance hit.t from the chain's last point) along *dir:
// the ray reflects with probability R (weight 1) or passes (*weight times the tint), by a hash of the crossing, so the
// same input gives the same bits. Returns whether it passed.
inline bool cross_glass_at_random(__global const Material* materials, __global const TextureInfo* textures,
                                  __global const uint* texels, SurfacePoint* s, TraceHit hit, uint k, float3* dir,
                                  float3* weight) {
  float3 through, mirror, tint;
  const float r = glass_crossing(materials, textures, texels, s, *dir, hit.t, false, &through, &mirror, &tint);
  const float u = random01((uint)hit.prim * GLASS_MAX_CROSSINGS + k, as_uint(hit.u) ^ as_uint(dir->x),
                           as_uint(hit.v) ^ as_uint(dir->y));
  if (u < r) {
    *dir = mirror;
    return false;
  }
  *dir = through;
  *weight *= tint;
  return true;
}

// A ray that reached glass along *dir (hit: its glass point, at distance hit->t) goes on through it as a light path
// does: at each glass point it reflects with probability R (weight 1) or passes with 1 - R (weight: the tint), by a
// hash of the crossing, so the same input gives the same bits. Returns the weight of the chain; *hit becomes the
// first hit that is not glass (prim -1: the ray left the scene), *dir its direction, *distance the chain's length.
// A ray still in glass after GLASS_MAX_CROSSINGS crossings is absorbed (weight 0).
// *met_volume: whether the chain passed into or out of glass with a volume (light it only reflected off a volume's
// face is not the volume's to carry: thin glass's reflections reach no shadow ray either).
inline float3 pass_glass_noting_volumes(BVH_ARGS, RayTally* rays, TraceHit* hit, float3* dir, float* distance,
                                        bool* met_volume) {
  float3 weight = (float3)(1.0f);
  *distance = hit->t;
  *met_volume = false;
  for (uint k = 0u; hit->prim >= 0 && is_glass(triangles, materials, textures, texels, hit->prim, hit->u, hit->v); ++k) {
    if (k == GLASS_MAX_CROSSINGS) return (float3)(0.0f);
    SurfacePoint s = surface_at(triangles, hit->prim, hit->u, hit->v);
    if (cross_glass_at_random(materials, textures, texels, &s, *hit, k, dir, &weight))
      *met_volume |= materials[s.material].thickness > 0.0f;
    if (!closest_hit(BVH, rays, leaving_origin(&s, *dir), *dir, hit)) hit->prim = -1;
    else *distance += hit->t;
  }
  return weight;
}

inline float3 pass_glass(BVH_ARGS, RayTally* rays, TraceHit* hit, float3* dir, float* distance) {
  bool met_volume;
  return pass_glass_noting_volumes(BVH, rays, hit, dir, distance, &met_volume);
}

// pass_glass for a hit a kernel traced and kept (the split and wavefront record and glossy traces): *hit becomes the
// first hit that is not glass, its t the chain's length (INFINITY where the ray left the scene), *dir its direction.
// Returns what the glass kept.
inline float3 kept_hit_past_glass(BVH_ARGS, RayTally* rays, HitDesc* hit, float3* dir) {
  TraceHit chain = {hit->t, hit->u, hit->v, hit->prim};
  float distance;
  const float3 weight = pass_glass(BVH, rays, &chain, dir, &distance);
  hit->t = chain.prim >= 0 ? distance : INFINITY;
  hit->u = chain.u;
  hit->v = chain.v;
  hit->prim = chain.prim;
  return weight;
}

// What of the light along a shadow ray (from `from` along to_offset up to tmax, as visible() takes it) gets through:
// 0 where something opaque blocks it, and through glass each crossing's 1 - R times its tint, straight on (exact for
// thin-walled glass, and for a slab of parallel faces but for the light's sideways shift; the light a curved volume
// would focus or bend is not followed). With HAS_GLASS_CAUSTICS (--light-through-glass caustics) a volume blocks it:
// the light a volume passes comes by the glass caustic map instead (kernels/glass_caustics.cl).
inline float3 light_transmittance(BVH_ARGS, float3 from, float3 to_offset, float tmax, RayTally* rays) {
  float3 weight = (float3)(1.0f);
  const bool toward_point = !isinf(tmax);
  const float3 target = toward_point ? from + tmax * to_offset : (float3)(0.0f);
  for (uint k = 0u;; ++k) {
    HitDesc answer;
    TraceHit hit;
    if (traced_or_queued(rays, from, to_offset, tmax, true, &answer)) {
      hit.t = answer.t;
      hit.u = answer.u;
      hit.v = answer.v;
      hit.prim = answer.prim;
    } else {
      RayPrecomp r = ray_precompute(from, to_offset);
      if (!bvh_trace(BVH, &r, 0.0f, tmax, false, &hit)) hit.prim = -1;
    }
    if (hit.prim < 0) return weight;
    if (k == GLASS_MAX_CROSSINGS || !is_glass(triangles, materials, textures, texels, hit.prim, hit.u, hit.v))
      return (float3)(0.0f);
    SurfacePoint s = surface_at(triangles, hit.prim, hit.u, hit.v);
#if HAS_GLASS_CAUSTICS
    if (materials[s.material].thickness > 0.0f) return (float3)(0.0f);
#endif
    const float length_per_t = length(to_offset);
    const float3 dir = to_offset / length_per_t;
    float3 through, mirror, tint;
    const float r =
        glass_crossing(materials, textures, texels, &s, dir, hit.t * length_per_t, true, &through, &mirror, &tint);
    weight *= (1.0f - r) * tint;
    if (!any_positive(weight)) return weight;
    from = leaving_origin(&s, dir);
    if (toward_point) {  // the rest of the segment: the far point stays where it was
      to_offset = target - from;
      tmax = 1.0f;
      if (!(dot(to_offset, dir) > 0.0f)) return weight;
    }
  }
}

#if HAS_GLASS_CAUSTICS
// What of the light from a direction a ray leaving `from` along *dir (unit) brings back gets through, where light by
// direction is gathered (the environment's smooth part, which the glass caustic map does not shoot): thin-walled glass
// as light_transmittance passes it, straight with its 1 - R and tint; a volume as pass_glass crosses it, reflected or
// refracted at random, so *dir becomes the direction the light arrives from. 0 where something opaque blocks it.
inline float3 escape_transmittance(BVH_ARGS, float3 from, float3* dir, RayTally* rays) {
  float3 weight = (float3)(1.0f);
  for (uint k = 0u;; ++k) {
    TraceHit hit;
    if (!closest_hit(BVH, rays, from, *dir, &hit)) return weight;
    if (k == GLASS_MAX_CROSSINGS || !is_glass(triangles, materials, textures, texels, hit.prim, hit.u, hit.v))
      return (float3)(0.0f);
    SurfacePoint s = surface_at(triangles, hit.prim, hit.u, hit.v);
    if (materials[s.material].thickness > 0.0f) {
      cross_glass_at_random(materials, textures, texels, &s, hit, k, dir, &weight);
    } else {
      float3 through, mirror, tint;
      weight *= (1.0f - glass_crossing(materials, textures, texels, &s, *dir, hit.t, true, &through, &mirror, &tint)) *
                tint;
      if (!any_positive(weight)) return weight;
    }
    from = leaving_origin(&s, *dir);
  }
}
#endif
#endif

#endif
