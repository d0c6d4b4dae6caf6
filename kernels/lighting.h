// Direct light at a surface point, shared by the direct pass, the record pass and the path tracer: punctual lights with
// shadow rays, and one sample of the emissive triangles chosen by power. Lambertian surfaces; emission is not included.
#ifndef RCSPLAT_LIGHTING_H
#define RCSPLAT_LIGHTING_H
#include "ray_queue.h"
#include "sampling.h"
#include "traverse.h"
#include "glass.h"

// Whether nothing blocks the segment from `from` along to_offset up to tmax (1: a point, INFINITY: a direction).
// Counts the shadow ray in *rays; in the wavefront trace the queue may answer it (kernels/ray_queue.h).
inline bool visible(BVH_ARGS, float3 from, float3 to_offset,
                    float tmax, RayTally* rays) {
  HitDesc answer;
  if (traced_or_queued(rays, from, to_offset, tmax, false, &answer)) return answer.prim < 0;
  RayPrecomp r = ray_precompute(from, to_offset);
  TraceHit h;
  return !bvh_trace(BVH, &r, 0.0f, tmax, true, &h);
}

// What of the light along a shadow ray (as visible() takes it) arrives: 1 or 0, and through glass its transmittance
// (kernels/glass.h). Multiplying by 1 changes no bit, so a scene without glass keeps its image.
inline float3 light_passes(BVH_ARGS, float3 from, float3 to_offset, float tmax, RayTally* rays) {
#if HAS_TRANSMISSION
  return light_transmittance(BVH, from, to_offset, tmax, rays);
#else
  return visible(BVH, from, to_offset, tmax, rays) ? (float3)(1.0f) : (float3)(0.0f);
#endif
}

// What sampling the emitters reads: the emitters, and where some emission is textured, the triangles' texture
// coordinates and the texels (named apart from BVH_ARGS's, which an alpha mask adds).
#if HAS_EMISSIVE_TEXTURES
#define EMITTER_ARGS                                                                                                 \
  __global const EmissiveTriangle *emitters, __global const TriangleShading *emitter_triangles,                    \
      __global const Material *emitter_materials, __global const TextureInfo *emitter_textures,                     \
      __global const uint *emitter_texels
#define EMITTERS emitters, triangles, materials, textures, texels
#define EMITTERS_PASSED_ON emitters, emitter_triangles, emitter_materials, emitter_textures, emitter_texels
#else
#define EMITTER_ARGS __global const EmissiveTriangle *emitters
#define EMITTERS emitters
#define EMITTERS_PASSED_ON emitters
#endif

#if HAS_PUNCTUAL_LIGHTS
// Irradiance at p (normal n, geometric normal ng) from one punctual light, shadowed; *wi is the unit direction
// toward the light.
inline float3 punctual_irradiance(BVH_ARGS, PunctualLight light,
                                  float3 p, float3 origin, float3 n, float3 ng, float3* wi_out, RayTally* rays) {
  float3 intensity = vload3(0, light.intensity);
  if (light.type == LIGHT_DIRECTIONAL) {
    float3 wi = -vload3(0, light.direction);
    *wi_out = wi;
    float cos_n = dot(n, wi);
    if (cos_n <= 0.0f || dot(ng, wi) <= 0.0f) return (float3)(0.0f);
    return intensity * cos_n * light_passes(BVH, origin, wi, INFINITY, rays);
  }
  float3 to_light = vload3(0, light.position) - p;
  float d2 = dot(to_light, to_light);
  *wi_out = n;
  if (!(d2 > 0.0f)) return (float3)(0.0f);
  float d = sqrt(d2);
  float3 wi = to_light / d;
  *wi_out = wi;
  float cos_n = dot(n, wi);
  if (cos_n <= 0.0f || dot(ng, wi) <= 0.0f) return (float3)(0.0f);
  float attenuation = 1.0f / d2;
  if (light.range > 0.0f) {  // glTF's recommended windowing, zero at the range
    float x = d / light.range;
    attenuation *= clamp(1.0f - x * x * x * x, 0.0f, 1.0f);
  }
  if (light.type == LIGHT_SPOT) {
    float cd = dot(vload3(0, light.direction), -wi);
    float a = clamp(cd * light.spot_scale + light.spot_offset, 0.0f, 1.0f);
    attenuation *= a * a;
  }
  if (attenuation <= 0.0f) return (float3)(0.0f);
  float3 to = vload3(0, light.position) - origin;
  return intensity * (attenuation * cos_n) * light_passes(BVH, origin, to, 1.0f, rays);
}
#endif

#if HAS_EMITTERS
// The emitter a uniform number u selects (binary search over the power CDF).
inline int pick_emitter(__global const EmissiveTriangle* emitters, uint count, float u) {
  int lo = 0, hi = (int)count - 1;
  while (lo < hi) {
    int mid = (lo + hi) >> 1;
    if (u < emitters[mid].cdf) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

// The density, per solid angle at a point d2 away, of the light sampler choosing a point on emitter e seen at cos_y.
inline float emitter_solid_angle_pdf(EmissiveTriangle e, float d2, float cos_y) {
  return e.pdf_select / e.area * d2 / cos_y;
}

// One light sample's irradiance estimate at p from the point the stratified pair (u, v) picks on the emitters;
// *wi is the sample's direction and *pdf its density per solid angle (0 where the estimate is 0), for weighing it
// against BRDF samples.
inline float3 emitter_sample(BVH_ARGS, EMITTER_ARGS, uint count, float u, float v, float3 p,
                             float3 origin, float3 n, float3 ng, float3* wi_out, float* pdf, RayTally* rays) {
  *pdf = 0.0f;
  *wi_out = n;
  int i = pick_emitter(emitters, count, u);
  EmissiveTriangle e = emitters[i];
  float cdf_before = e.cdf - e.pdf_select;
  float u_in = clamp((u - cdf_before) / e.pdf_select, 0.0f, 0.99999994f);  // reuse u inside the chosen stratum
  float su = sqrt(u_in);
  float3 e1 = vload3(0, e.edge1), e2 = vload3(0, e.edge2);
  float3 y = vload3(0, e.v0) + (su * (1.0f - v)) * e1 + (su * v) * e2;
  float3 nl = normalize(cross(e1, e2));
  float3 to = y - p;
  float d2 = dot(to, to);
  if (!(d2 > 0.0f)) return (float3)(0.0f);
  float3 wi = to * rsqrt(d2);
  *wi_out = wi;
  float cos_x = dot(n, wi);
  float cos_y = -dot(nl, wi);
  if (emitter_double_sided(e)) cos_y = fabs(cos_y);
  if (cos_x <= 0.0f || cos_y <= 0.0f || dot(ng, wi) <= 0.0f) return (float3)(0.0f);
  float3 toward_p = dot(nl, wi) < 0.0f ? nl : -nl;
  float3 target = offset_ray_origin(y, toward_p);
  const float3 passes = light_passes(BVH, origin, target - origin, 1.0f, rays);
  if (!any_positive(passes)) return (float3)(0.0f);
  float pdf_area = e.pdf_select / e.area;
  *pdf = emitter_solid_angle_pdf(e, d2, cos_y);
#if HAS_EMISSIVE_TEXTURES
  const float3 radiance = emitter_radiance_at(e, su * (1.0f - v), su * v, emitter_triangles, emitter_materials,
                                              emitter_textures, emitter_texels);
#else
  const float3 radiance = vload3(0, e.radiance);
#endif
  return radiance * (cos_x * cos_y / (d2 * pdf_area)) * passes;
}
#endif

// Irradiance at p from every punctual light plus one emitter sample at the uniform pair (u, v).
inline float3 direct_irradiance(BVH_ARGS,
                                __global const PunctualLight* lights, uint light_count,
                                EMITTER_ARGS, uint emitter_count, float3 p, float3 n,
                                float3 ng, float u, float v, RayTally* rays) {
  float3 origin = offset_ray_origin(p, ng);
  float3 irradiance = (float3)(0.0f);
  float3 wi;
#if HAS_PUNCTUAL_LIGHTS
  for (uint i = 0; i < light_count; ++i) irradiance += punctual_irradiance(BVH, lights[i], p, origin, n, ng, &wi, rays);
#endif
#if HAS_EMITTERS
  float pdf;
  if (emitter_count > 0)
    irradiance += emitter_sample(BVH, EMITTERS_PASSED_ON, emitter_count, u, v, p, origin, n, ng, &wi, &pdf, rays);
#endif
  return irradiance;
}

#endif
