// The normal a pixel shades with. The G-buffer's `normal` is the interpolated one: the cache places, weighs and
// extrapolates records by it, as the method defines them on smooth surfaces. Where a normal map bends it
// (HAS_NORMAL_MAPS), the bent normal rides along in two floats, octahedral-encoded (an exact inverse to a few ULPs),
// and direct light, BRDFs, the glossy pass, path tracing and the diffuse light's rotation gradient read it here.
#ifndef RCSPLAT_SHADING_NORMAL_H
#define RCSPLAT_SHADING_NORMAL_H
#include "shared_types.h"

// Programs built with the scene's switches compile this only for a scene with normal maps; those built once for every
// scene (the splats, the layers: no HAS_NORMAL_MAPS defined) test the pixel's marker, which a scene without normal
// maps never sets, so that they give the same bits as before.
#ifdef HAS_NORMAL_MAPS
#define READS_MAPPED_NORMALS HAS_NORMAL_MAPS
#else
#define READS_MAPPED_NORMALS 1
#endif

#if READS_MAPPED_NORMALS
inline float sign_not_zero(float x) { return x >= 0.0f ? 1.0f : -1.0f; }

// A unit vector to the octahedron's square [-1, 1]^2 and back (the octahedral map: the lower half folds outward).
inline float2 octahedral_encode(float3 n) {
  float2 p = n.xy / (fabs(n.x) + fabs(n.y) + fabs(n.z));
  if (n.z < 0.0f) p = (float2)((1.0f - fabs(p.y)) * sign_not_zero(p.x), (1.0f - fabs(p.x)) * sign_not_zero(p.y));
  return p;
}

inline float3 octahedral_decode(float2 p) {
  float3 n = (float3)(p.x, p.y, 1.0f - fabs(p.x) - fabs(p.y));
  if (n.z < 0.0f) n.xy = (float2)((1.0f - fabs(p.y)) * sign_not_zero(p.x), (1.0f - fabs(p.x)) * sign_not_zero(p.y));
  return normalize(n);
}
#endif

// The pixel's shading normal: its normal map's where it has one, else the interpolated normal.
inline float3 gbuffer_shading_normal(GBufferSample g) {
#if READS_MAPPED_NORMALS
  if (g.mapped_normal[0] != NO_MAPPED_NORMAL) return octahedral_decode(vload2(0, g.mapped_normal));
#endif
  return vload3(0, g.normal);
}

// The layers the G-buffer kept beside sample i (gbuffer_layers), in scenes with them; nothing is read otherwise.
inline SurfaceLayers pixel_layers(__global const SurfaceLayers* gbuffer_layers, size_t i) {
#if HAS_LAYERS
  return gbuffer_layers[i];
#else
  SurfaceLayers none = {{1.0f, 1.0f, 1.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, 1.0f, {0.0f, 0.0f, 0.0f}, 1.0f};
  return none;
#endif
}

#endif
