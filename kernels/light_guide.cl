// The light guide's photons (host/passes/light_guide_pass.h): each work-item sends one photon from a light (punctual,
// emissive triangle, the environment's peak, a sun: kernels/environment.h, or for the bounce probe alone the sky's
// smooth part: PhotonParams::sky_source), chosen in proportion to its power, to the first surface it lands on, and
// records the flux arriving there and the flux that surface reflects (power times albedo). The host clusters the hits
// into the few bright places records should aim rays at. With more landings the photons go on, reflected by each
// surface's BRDF, and their later landings make the photon map of --bounce-method photons
// (host/passes/photon_map_pass.h).
#include "environment.h"
#include "light_guide.h"
#include "scene_args.h"
#include "surface.h"
#include "traverse.h"
#if HAS_SPECULAR_BRDF
#include "reflected_light.h"
#endif

// Landing k's reflection draws its direction from dimensions 6 + 2k, 7 + 2k of the photon's stream and, on a surface
// with a specular lobe, its lobe from PHOTON_LOBE_DIMENSION + k.
#define PHOTON_LOBE_DIMENSION 64u

// The direction a photon that arrived along dir leaves the surface *h in, drawn from the BRDF; *power becomes what
// leaves. A Lambertian surface: a cosine-weighted direction, and *power is `reflected` (power times albedo). With a
// specular lobe the photon is the light the surface reflects toward its new direction, f(new, arrived) cos(new) / pdf
// (the BRDF's view is the new direction: its diffuse base's Fresnel depends on it, so the weight is not the one
// brdf_sample returns for a path).
inline float3 scatter_photon(SCENE_ARGS, HitSurface* h, float3 dir, float3 reflected, uint key, uint k,
                             float3* power) {
  float u1 = random01(key, 0u, 6u + 2u * k), u2 = random01(key, 0u, 7u + 2u * k);
#if HAS_SPECULAR_BRDF
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  if (lobe.lobe != LOBE_NONE) {
    ShadingFrame frame = shading_frame(h->ns);
    BrdfInputs in = surface_brdf(hit_albedo(materials, textures, texels, h), lobe, h->ns);
    float3 arrived = view_local(frame, -dir), next;
    float pdf;
    brdf_sample(in, arrived, random01(key, 0u, PHOTON_LOBE_DIMENSION + k), u1, u2, &next, &pdf);
    *power = pdf > 0.0f ? *power * brdf_eval(in, next, arrived) * (next.z / pdf) : (float3)(0.0f);
    return to_world(frame, next);
  }
#endif
  float3 t, b;
  tangent_frame(h->ns, &t, &b);
  *power = reflected;
  return cosine_direction(t, b, h->ns, u1, u2);
}

#if HAS_SPECULAR_BRDF
// The caustic map's reflection at landing 0 (PhotonParams::caustic): a photon goes on only from a surface whose lobe is
// sharp (LOBE_GLOSSY, the lobes kernels/bounce.h hit_direct_without_caustics leaves to the map), along a direction
// drawn from that lobe's visible normals seen from the light, carrying f_specular cos / pdf = F G2 / G1 of its power
// (brdf_specular_weight, which is symmetric in the two directions); the diffuse base's light stays with the records.
// Layers' lobes are weighed by the view's Fresnel, so they are not symmetric: lobes_adjoint_weight evaluates them
// toward the photon's new direction.
inline float3 scatter_caustic_photon(SCENE_ARGS, HitSurface* h, float3 dir, uint key, float3* power) {
  SurfaceLobe lobe = hit_lobe(materials, textures, texels, h);
  if (lobe.lobe != LOBE_GLOSSY) {
    *power = (float3)(0.0f);
    return dir;
  }
  ShadingFrame frame = shading_frame(h->ns);
  BrdfInputs in = surface_brdf(hit_albedo(materials, textures, texels, h), lobe, h->ns);
  float3 toward_light = view_local(frame, -dir);
  float3 next = lobes_sample(in, toward_light, random01(key, 0u, PHOTON_LOBE_DIMENSION), random01(key, 0u, 6u),
                             random01(key, 0u, 7u));
  *power *= lobes_adjoint_weight(in, toward_light, next);
  return to_world(frame, next);
}
#endif

// A point of the unit disc facing axis, from uniform (u, v): photons of lights at infinity cross it.
inline float3 unit_disc_point(float3 axis, float u, float v) {
  float3 t, b;
  tangent_frame(axis, &t, &b);
  float r = sqrt(u), cos_p, sin_p = sincos(2.0f * RC_PI * v, &cos_p);
  return (r * cos_p) * t + (r * sin_p) * b;
}

// Where a photon comes from, for aiming it (below): a light at infinity (a unit disc facing it), a point (isotropic or
// a spot) or an emitting surface.
#define PHOTON_FROM_INFINITY 0u
#define PHOTON_FROM_POINT 1u
#define PHOTON_FROM_SPOT 2u
#define PHOTON_FROM_SURFACE 3u

#if HAS_GLASS_CAUSTICS
// The glass caustic map's photons (PhotonParams::glass_caustics spheres) go only toward the glass volumes: aimed at
// their bounding spheres (xyz centre, w radius, device frame), one picked uniformly, so that a small vase in a large
// room still gathers its photons. Their power is what the light sends that way over the density of the aimed choice.
#define PHOTON_AIM_DIMENSION 96u

// The cone from origin that sphere s fills: its axis and 1 - cos of its half-angle (2: origin is inside, every
// direction).
inline float3 sphere_cone(float4 s, float3 origin, float* one_minus_cos) {
  const float3 to = s.xyz - origin;
  const float d2 = dot(to, to), r2 = s.w * s.w;
  if (!(d2 > r2)) {
    *one_minus_cos = 2.0f;
    return (float3)(0.0f, 0.0f, 1.0f);
  }
  const float x = r2 / d2;
  *one_minus_cos = x / (1.0f + sqrt(1.0f - x));  // 1 - sqrt(1 - x), without cancellation for small spheres
  return to * rsqrt(d2);
}

// A direction from origin uniform in sphere k's cone by (v, w); *density: its density per solid angle over every
// sphere's cone, each sphere picked with probability 1 / count.
inline float3 toward_spheres(__global const float4* spheres, uint count, float3 origin, uint k, float v, float w,
                             float* density) {
  float own;
  const float3 axis = sphere_cone(spheres[k], origin, &own);
  const float3 dir = cone_direction(axis, v * own, w);
  float sum = 0.0f;
  for (uint j = 0u; j < count; ++j) {
    float one_minus_cos;
    const float3 a = sphere_cone(spheres[j], origin, &one_minus_cos);
    if (j != k && 1.0f - dot(dir, a) <= one_minus_cos) sum += 1.0f / (2.0f * RC_PI * one_minus_cos);
  }
  *density = (sum + 1.0f / (2.0f * RC_PI * own)) / (float)count;  // dir lies in its own cone, whatever rounding says
  return dir;
}

// A point of the plane through the device frame's centre facing dir, uniform in sphere k's shadow on it (a disc) by
// (u, v); *density: its density per area over every sphere's disc.
inline float3 across_spheres(__global const float4* spheres, uint count, float3 dir, uint k, float u, float v,
                             float* density) {
  const float4 s = spheres[k];
  const float3 p = s.xyz - dot(s.xyz, dir) * dir + s.w * unit_disc_point(dir, u, v);
  float sum = 1.0f / (RC_PI * s.w * s.w);  // p lies in its own disc, whatever rounding says
  for (uint j = 0u; j < count; ++j) {
    const float4 o = spheres[j];
    const float3 d = p - (o.xyz - dot(o.xyz, dir) * dir);
    if (j != k && dot(d, d) <= o.w * o.w) sum += 1.0f / (RC_PI * o.w * o.w);
  }
  *density = sum / (float)count;
  return p;
}
#endif

__kernel void shoot_photons(SCENE_ARGS, __global const float* source_cdf, __global const float4* glass_targets,
                            PhotonParams params, __global PhotonHit* photons) {
  uint i = get_global_id(0);
  if (i >= params.photon_count) return;
  uint key = hash_u32(i ^ hash_u32(params.seed));
  int source = (int)cdf_bin(source_cdf, params.source_count, random01(key, 0u, 0u));
  float select = source_cdf[source] - (source > 0 ? source_cdf[source - 1] : 0.0f);
  float u = random01(key, 0u, 1u), v = random01(key, 0u, 2u);
  float3 origin, dir, power;
  uint photon_from = PHOTON_FROM_POINT;  // how a glass caustic photon is aimed (HAS_GLASS_CAUSTICS)
  float3 emitting_side = (float3)(0.0f);
#if HAS_ENVIRONMENT
  if (params.sky_source && source == (int)params.source_count - 1) {
    // The sky's smooth part: a direction uniform over the sphere, the photon entering through the unit disc facing it
    // beyond the scene, carrying radiance times the disc's area over the direction's density, L pi 4 pi.
    float3 toward = cone_direction((float3)(0.0f, 0.0f, 1.0f), 2.0f * u, v);
    origin = unit_disc_point(toward, random01(key, 0u, 4u), random01(key, 0u, 5u)) + 2.0f * toward;
    dir = -toward;
    power = environment_smooth(environment, scene_counts, toward) * (4.0f * RC_PI * RC_PI);
  } else
#endif
  if (source < (int)scene_counts.light_count) {
    PunctualLight light = lights[source];
    float3 intensity = vload3(0, light.intensity), axis = vload3(0, light.direction);
    if (light.type == LIGHT_DIRECTIONAL) {
      // Through a unit disc facing the light, beyond the scene (the device frame fits it in the unit sphere).
      origin = unit_disc_point(axis, u, v) - 2.0f * axis;
      dir = axis;
      power = intensity * RC_PI;
      photon_from = PHOTON_FROM_INFINITY;
    } else if (light.type == LIGHT_SPOT) {
      float cos_outer = clamp(-light.spot_offset / light.spot_scale, -1.0f, 1.0f);
      dir = cone_direction(axis, u * (1.0f - cos_outer), v);
      float a = clamp(dot(dir, axis) * light.spot_scale + light.spot_offset, 0.0f, 1.0f);
      origin = vload3(0, light.position);
      power = intensity * (2.0f * RC_PI * (1.0f - cos_outer)) * (a * a);
      photon_from = PHOTON_FROM_SPOT;
    } else {
      dir = cone_direction((float3)(0.0f, 0.0f, 1.0f), 2.0f * u, v);
      origin = vload3(0, light.position);
      power = intensity * (4.0f * RC_PI);
    }
  }
#if HAS_ENVIRONMENT
  else if (source == (int)(scene_counts.light_count + scene_counts.emitter_count)) {
    // The peak: a direction drawn by its importance sampling, the photon entering through a unit disc facing it
    // beyond the scene (as a directional light's), carrying radiance / density times the disc's area.
    float pdf;
    float3 toward;
    float3 radiance_over_pdf =
        environment_peak_sample(environment, environment_cdf, scene_counts, u, v, &toward, &pdf);
    origin = unit_disc_point(toward, random01(key, 0u, 4u), random01(key, 0u, 5u)) + 2.0f * toward;
    dir = -toward;
    power = pdf > 0.0f ? radiance_over_pdf * RC_PI : (float3)(0.0f);
    photon_from = PHOTON_FROM_INFINITY;
  }
#endif
  else {
    EmissiveTriangle e = emitters[source - (int)scene_counts.light_count];
    float su = sqrt(u);
    float3 e1 = vload3(0, e.edge1), e2 = vload3(0, e.edge2);
    float3 y = vload3(0, e.v0) + (su * (1.0f - v)) * e1 + (su * v) * e2;
    float3 n = normalize(cross(e1, e2));
    float sides = emitter_double_sided(e) ? 2.0f : 1.0f;
    if (emitter_double_sided(e) && random01(key, 0u, 3u) < 0.5f) n = -n;
    // Cosine-weighted: the emitted power per photon is then pi L area per side.
    float u2 = random01(key, 0u, 4u), v2 = random01(key, 0u, 5u);
    float r = sqrt(u2), cos_p, sin_p = sincos(2.0f * RC_PI * v2, &cos_p);
    float3 t, b;
    tangent_frame(n, &t, &b);
    dir = (r * cos_p) * t + (r * sin_p) * b + sqrt(fmax(1.0f - u2, 0.0f)) * n;
    origin = offset_ray_origin(y, n);
    // Where the photon leaves, as the light sampler reads it.
    const float3 radiance = emitter_radiance_at(e, su * (1.0f - v), su * v, triangles, materials, textures, texels);
    power = radiance * (RC_PI * e.area * sides);
    photon_from = PHOTON_FROM_SURFACE;
    emitting_side = n;
  }
#if HAS_GLASS_CAUSTICS
  if (params.glass_caustics > 0u) {
    // Aimed at the glass volumes, the photon's power becomes what the source sends along its new way over the aimed
    // density (each branch above drew it from a density its power divides out: pi for a unit disc, 4 pi for a point
    // light's sphere, cos / pi for an emitter's cosine lobe).
    const uint target = min((uint)(random01(key, 0u, PHOTON_AIM_DIMENSION) * (float)params.glass_caustics),
                            params.glass_caustics - 1u);
    const float u_aim = random01(key, 0u, PHOTON_AIM_DIMENSION + 1u), v_aim = random01(key, 0u, PHOTON_AIM_DIMENSION + 2u);
    float density;
    if (photon_from == PHOTON_FROM_INFINITY) {
      origin = across_spheres(glass_targets, params.glass_caustics, dir, target, u_aim, v_aim, &density) - 2.0f * dir;
      power *= 1.0f / (RC_PI * density);
    } else {
      dir = toward_spheres(glass_targets, params.glass_caustics, origin, target, u_aim, v_aim, &density);
      if (photon_from == PHOTON_FROM_POINT) {
        power *= 1.0f / (4.0f * RC_PI * density);
      } else if (photon_from == PHOTON_FROM_SPOT) {
        PunctualLight light = lights[source];
        const float a = clamp(dot(dir, vload3(0, light.direction)) * light.spot_scale + light.spot_offset, 0.0f, 1.0f);
        power = vload3(0, light.intensity) * (a * a / density);
      } else {
        power *= fmax(dot(dir, emitting_side), 0.0f) / (RC_PI * density);
      }
    }
  }
#endif
  // Landing 0 is the first surface (the light guide reads only it); with params.landings > 1 the photon goes on,
  // reflected by the surface's BRDF (scatter_photon), and lands params.landings times at most (the photon map,
  // kernels/photon_map.h, keeps landings 1 ..).
  bool alive = select > 0.0f;
  for (uint k = 0; k < params.landings; ++k) {
    PhotonHit out;
    out.hit = 0;
    out.landing = (int)k;
    out.pad1 = out.pad2 = 0.0f;
    vstore3((float3)(0.0f), 0, out.position);
    vstore3((float3)(0.0f), 0, out.normal);
    vstore3((float3)(0.0f), 0, out.flux);
    vstore3((float3)(0.0f), 0, out.incident);
    RayPrecomp r = ray_precompute(origin, dir);
    TraceHit hit;
    bool landed = alive && bvh_trace(BVH, &r, 0.0f, INFINITY, false, &hit);
#if HAS_TRANSMISSION
    if (landed) {  // glass is no landing: the photon goes on through it (kernels/glass.h), keeping what it passes
      RayTally glass_rays = traced_rays(0u);
      float chain;
      bool met_volume;
      power *= pass_glass_noting_volumes(BVH, &glass_rays, &hit, &dir, &chain, &met_volume);
      landed = hit.prim >= 0 && (met_volume || !params.glass_caustics);
    }
#endif
    if (landed) {
      HitSurface h = photon_hit_surface(triangles, hit.prim, hit.u, hit.v, dir);
      const float per_photon = select * (float)params.photon_count;
      float3 reflected = power * hit_albedo(materials, textures, texels, &h);
      float3 flux = finite_or_zero(reflected / per_photon);
      out.hit = 1;
      vstore3(h.s.position, 0, out.position);
      vstore3(h.ng, 0, out.normal);
      vstore3(flux, 0, out.flux);
      vstore3(finite_or_zero(power / per_photon), 0, out.incident);
      if (k + 1u < params.landings) {
#if HAS_SPECULAR_BRDF
        if (params.caustic) dir = scatter_caustic_photon(SCENE, &h, dir, key, &power);
        else
#endif
          dir = scatter_photon(SCENE, &h, dir, reflected, key, k, &power);
        float3 leaving = finite_or_zero(power / per_photon);
        alive = dot(dir, h.ng) > 0.0f && any_positive(leaving);
        origin = offset_ray_origin(h.s.position, h.ng);
      }
    } else {
      alive = false;
    }
    if (k >= params.first_stored)
      photons[(size_t)i * (params.landings - params.first_stored) + (k - params.first_stored)] = out;
  }
}
