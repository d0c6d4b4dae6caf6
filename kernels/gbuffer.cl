// Primary visibility: what the ray through each pixel's centre (or a jittered point of it) hits, with its normals, albedo and emission (where it
// leaves the scene, the environment it sees).
#include "traverse.h"
#include "environment.h"
#include "scene_args.h"
#include "surface.h"
#include "shading_normal.h"
#include "counter_random.h"
#include "glass.h"

// Where in pixel (x, y) its camera ray passes, in pixels from its top-left corner: the centre of the camera's jitter
// cell, a random point of it, or, in the s-times larger frame of s x s pixel samples, a point of a rotated grid.
inline float2 pixel_offset(__global const CameraParams* cam, int x, int y) {
  float2 u = (float2)(0.5f);
  if (cam->jitter_seed) {
    uint pixel = (uint)(y * cam->width + x);
    u = (float2)(random01(cam->jitter_seed, pixel, 0u), random01(cam->jitter_seed, pixel, 1u));
  } else if (cam->sub_pixel_side > 1) {
    // Sub-pixel (i, j) of its output pixel moves within its cell to ((s - 1 - j + 1/2) / s, (i + 1/2) / s): the
    // output pixel's s^2 points then have s^2 different x and s^2 different y (a grid rotated by atan(1/s); 2 x 2
    // is the rotated-grid pattern of RGSS). A near-vertical or near-horizontal edge, which the cells' centres see in
    // steps of 1/s of the pixel, is seen in steps of 1/s^2, at no cost.
    const int s = cam->sub_pixel_side, i = x % s, j = y % s;
    u = (float2)(((float)(s - 1 - j) + 0.5f) / (float)s, ((float)i + 0.5f) / (float)s);
  }
  return vload2(0, cam->jitter_origin) + cam->jitter_cell * u;
}

inline float3 camera_ray_direction(__global const CameraParams* cam, int x, int y, float2 offset) {
  float sx = (2.0f * ((float)x + offset.x) / (float)cam->width - 1.0f) * cam->tan_half_fov_y * cam->aspect;
  float sy = (1.0f - 2.0f * ((float)y + offset.y) / (float)cam->height) * cam->tan_half_fov_y;
  return normalize(vload3(0, cam->forward) + sx * vload3(0, cam->right) + sy * vload3(0, cam->up));
}

// An orthographic camera's ray through pixel (x, y) starts on the plane through the eye, at the pixel's offset point.
inline float3 orthographic_ray_origin(__global const CameraParams* cam, int x, int y, float2 offset) {
  float sx = (2.0f * ((float)x + offset.x) / (float)cam->width - 1.0f) * cam->half_height * cam->aspect;
  float sy = (1.0f - 2.0f * ((float)y + offset.y) / (float)cam->height) * cam->half_height;
  return vload3(0, cam->eye) + sx * vload3(0, cam->right) + sy * vload3(0, cam->up);
}

#if HAS_TRANSMISSION
// What the mirror image in glass shows along dir from origin: the sky where the ray leaves the scene, an emitter's
// light where it meets one, through the glass on the way (passed as camera rays pass it: the light inside a slab
// mirrored by its far face leaves through its near one). Lit surfaces are kernels/glass_mirror.cl's: their light is
// not known when the G-buffer is made.
inline float3 mirrored_sources(SCENE_ARGS, float3 origin, float3 dir) {
  float3 weight = (float3)(1.0f);
  for (uint k = 0u; k < GLASS_MAX_CROSSINGS; ++k) {
    RayPrecomp r = ray_precompute(origin, dir);
    TraceHit hit;
    if (!bvh_trace(BVH, &r, 0.0f, INFINITY, false, &hit)) {
#if HAS_ENVIRONMENT
      return weight * environment_radiance(environment, scene_counts, dir);
#else
      return (float3)(0.0f);
#endif
    }
    SurfacePoint s = surface_at(triangles, hit.prim, hit.u, hit.v);
    if (!is_glass(triangles, materials, textures, texels, hit.prim, hit.u, hit.v)) {
      if (dot(s.geometric_normal, dir) > 0.0f && !materials[s.material].double_sided) return (float3)(0.0f);
      return weight * surface_emission(materials, textures, texels, &s);
    }
    float3 through, mirror, tint;
    const float reflectance = glass_crossing(materials, textures, texels, &s, dir, hit.t, false, &through, &mirror, &tint);
    if (!(reflectance < 1.0f)) return (float3)(0.0f);
    weight *= (1.0f - reflectance) * tint;
    dir = through;
    origin = leaving_origin(&s, dir);
  }
  return (float3)(0.0f);
}

// A camera ray that met glass looks through it (kernels/glass.h): at each glass point it passes (straight, or
// refracted into or out of a volume) keeping 1 - R times the glass's tint, or where glass reflects all (total internal
// reflection) follows the reflection, so every pixel sees one surface the cache can shade, never the glass. Each glass
// point adds to *reflection R times what its mirror image shows (mirrored_sources), weighed by what the glass before it
// kept; the first keeps the mirrored ray for the lit surfaces it meets (*mirror_from: origin and R, *mirror_toward:
// its direction; kernels/glass_mirror.cl).
// Returns the weight of the light from *hit, the first surface that is not glass (prim -1: none, the ray leaves along
// *dir); *distance is the chain's length. A ray still in glass after GLASS_MAX_CROSSINGS sees nothing (weight 0).
inline float3 camera_through_glass(SCENE_ARGS, TraceHit* hit, float3* dir, float* distance, float3* reflection,
                                   float4* mirror_from, float4* mirror_toward) {
  float3 weight = (float3)(1.0f);
  *reflection = (float3)(0.0f);
  *mirror_from = *mirror_toward = (float4)(0.0f);
  *distance = hit->t;
  for (uint k = 0u; hit->prim >= 0 && is_glass(triangles, materials, textures, texels, hit->prim, hit->u, hit->v); ++k) {
    if (k == GLASS_MAX_CROSSINGS) return (float3)(0.0f);
    SurfacePoint s = surface_at(triangles, hit->prim, hit->u, hit->v);
    float3 through, mirror, tint;
    const float r = glass_crossing(materials, textures, texels, &s, *dir, hit->t, false, &through, &mirror, &tint);
    if (r > 0.0f && r < 1.0f) {  // every face mirrors: a slab's far face too, seen through its near one
      const float3 from = leaving_origin(&s, mirror);
      *reflection += weight * r * mirrored_sources(SCENE, from, mirror);
      if (k == 0u) {
        *mirror_from = (float4)(from, r);
        *mirror_toward = (float4)(mirror, 0.0f);
      }
    }
    if (r < 1.0f) {
      weight *= (1.0f - r) * tint;
      *dir = through;
    } else {
      *dir = mirror;
    }
    RayPrecomp next = ray_precompute(leaving_origin(&s, *dir), *dir);
    if (!bvh_trace(BVH, &next, 0.0f, INFINITY, false, hit)) hit->prim = -1;
    else *distance += hit->t;
  }
  return weight;
}
#endif

// Multiplies each pixel's light (RGB) by what the glass its camera ray looked through kept (see_through), in scenes
// with glass; the direct light's pass runs it on its result.
__kernel void weigh_through_glass(__global const float4* see_through, uint pixel_count, __global float4* light) {
  const uint i = get_global_id(0);
  if (i >= pixel_count) return;
  light[i] = (float4)(light[i].xyz * see_through[i].xyz, light[i].w);
}

// Writes the G-buffer the other passes read through GBUFFER_ARGS, and in scenes with glass (HAS_TRANSMISSION) what the
// glass each camera ray looked through kept (see_through: RGB, 1 without glass), which weighs the pixel's direct and
// indirect light; what the glass mirrors of the sky and emitters is added to the pixel's emission, and the mirrored
// ray kept in glass_mirrors (two float4 a pixel) for the lit surfaces it meets. In scenes with layers (HAS_LAYERS) each
// pixel's layers go to gbuffer_layers.
__kernel void gbuffer(SCENE_ARGS, __global GBufferSample* gbuffer, __global const CameraParams* camera,
                      __global SurfaceLayers* gbuffer_layers, __global float4* see_through,
                      __global float4* glass_mirrors) {
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= camera->width || y >= camera->height) return;
  float2 offset = pixel_offset(camera, x, y);
  float3 org = camera->orthographic ? orthographic_ray_origin(camera, x, y, offset) : vload3(0, camera->eye);
  float3 dir = camera->orthographic ? vload3(0, camera->forward) : camera_ray_direction(camera, x, y, offset);
  RayPrecomp r = ray_precompute(org, dir);
  TraceHit hit;
  bool found = bvh_trace(BVH, &r, 0.0f, INFINITY, false, &hit);
  float3 through_glass = (float3)(1.0f), mirrored = (float3)(0.0f);
  float distance = hit.t;
#if HAS_TRANSMISSION
  float4 mirror_from = (float4)(0.0f), mirror_toward = (float4)(0.0f);
  if (found) {
    through_glass = camera_through_glass(SCENE, &hit, &dir, &distance, &mirrored, &mirror_from, &mirror_toward);
    found = hit.prim >= 0;
    hit.t = distance;
  }
  const size_t pixel = (size_t)y * camera->width + x;
  see_through[pixel] = (float4)(through_glass, 1.0f);
  glass_mirrors[2 * pixel] = mirror_from;
  glass_mirrors[2 * pixel + 1] = mirror_toward;
#endif
  GBufferSample g;
  g.mapped_normal[0] = NO_MAPPED_NORMAL;
  g.mapped_normal[1] = 0.0f;
  g.metallic = 0.0f;
  g.roughness = 1.0f;
  g.specular = 0.0f;
  g.lobe = LOBE_NONE;
  if (!found) {
    vstore3((float3)(0.0f), 0, g.position);
    vstore3((float3)(0.0f), 0, g.normal);
    vstore3((float3)(0.0f), 0, g.geometric_normal);
    vstore3((float3)(0.0f), 0, g.albedo);
#if HAS_ENVIRONMENT
    vstore3(environment_radiance(environment, scene_counts, dir) * through_glass + mirrored, 0, g.emission);  // the sky
#else
    vstore3(mirrored, 0, g.emission);
#endif
    g.triangle = -1;
    g.material = -1;
    g.depth = INFINITY;
#if HAS_LAYERS
    SurfaceLayers none;
    no_layers((float3)(0.0f, 0.0f, 1.0f), &none);
    gbuffer_layers[y * camera->width + x] = none;
#endif
  } else {
    HitSurface h = hit_surface(HIT_SURFACE, hit.prim, hit.u, hit.v, dir, primary_cone_width(camera, hit.t));
    SurfacePoint s = h.s;
    const float3 ng = h.ng, ns = h.ns;
    bool back = dot(s.geometric_normal, dir) > 0.0f;
    __global const Material* m = materials + s.material;
    float3 emission = (!back || m->double_sided) ? surface_emission(materials, textures, texels, &s) : (float3)(0.0f);
    emission = emission * through_glass + mirrored;
    vstore3(s.position, 0, g.position);
#if HAS_NORMAL_MAPS
    vstore3(h.ns_interpolated, 0, g.normal);
    if (m->normal_texture >= 0) vstore2(octahedral_encode(ns), 0, g.mapped_normal);
#else
    vstore3(ns, 0, g.normal);
#endif
    vstore3(ng, 0, g.geometric_normal);
    vstore3(surface_albedo(materials, textures, texels, &s), 0, g.albedo);
    vstore3(emission, 0, g.emission);
    g.triangle = hit.prim;
    g.material = (int)s.material;
#if HAS_SPECULAR_BRDF
    SurfaceLobe lobe = hit_lobe(materials, textures, texels, &h);
    g.metallic = lobe.metallic;
    g.roughness = lobe.roughness;
    g.specular = lobe.specular;
    g.lobe = lobe.lobe;
#if HAS_LAYERS
    gbuffer_layers[y * camera->width + x] = lobe.layers;
#endif
#endif
    g.depth = hit.t;
  }
  gbuffer[y * camera->width + x] = g;
}
