// What a ray hit: the surface point's normals, texture coordinates and material, and base-colour texture lookups.
#ifndef RCSPLAT_SURFACE_H
#define RCSPLAT_SURFACE_H
#include "host_device.h"
#include "shared_types.h"

typedef struct {
  float3 position;          // interpolated from the vertices
  float3 geometric_normal;  // unit, by winding
  float3 shading_normal;    // unit, interpolated
  float2 uv;
  uint material;
  // log2 of the texture-coordinate width of the ray's footprint here (-INFINITY: none known, texel-sized lookups).
  float uv_width_log2;
#if HAS_VERTEX_COLORS
  float3 color;  // interpolated vertex colour
#endif
} SurfacePoint;

#if HAS_VERTEX_COLORS
// A full channel is exactly 1 (the white that triangles without colours carry): compiling the vertex-colour code for
// a scene without colours then changes no bit of its image (tests/scene_plan_test.cpp).
inline float3 unpack_vertex_color(uint packed) {
  uint3 c = (uint3)(packed & VERTEX_COLOR_MAX, (packed >> VERTEX_COLOR_BITS) & VERTEX_COLOR_MAX,
                    (packed >> (2 * VERTEX_COLOR_BITS)) & VERTEX_COLOR_MAX);
  float3 scaled = convert_float3(c) * (1.0f / (float)VERTEX_COLOR_MAX);
  return select(scaled, (float3)(1.0f), c == (uint3)(VERTEX_COLOR_MAX));
}
#endif

inline SurfacePoint surface_at(__global const TriangleShading* triangles, int prim, float u, float v) {
  __global const TriangleShading* t = triangles + prim;
  SurfacePoint s;
  float w = 1.0f - u - v;
  s.position = w * vload3(0, t->v0) + u * vload3(0, t->v1) + v * vload3(0, t->v2);
  s.geometric_normal = vload3(0, t->geometric_normal);
  float3 n = w * vload3(0, t->normal0) + u * vload3(0, t->normal1) + v * vload3(0, t->normal2);
  float len = length(n);
  s.shading_normal = len > 0.0f ? n / len : s.geometric_normal;
  s.uv = w * vload2(0, t->uv0) + u * vload2(0, t->uv1) + v * vload2(0, t->uv2);
  s.material = t->material;
  s.uv_width_log2 = -INFINITY;
#if HAS_VERTEX_COLORS
  // A triangle of one colour takes it as it is: barycentric weights need not sum to exactly 1 in float.
  if (t->color[0] == t->color[1] && t->color[1] == t->color[2]) s.color = unpack_vertex_color(t->color[0]);
  else
    s.color = w * unpack_vertex_color(t->color[0]) + u * unpack_vertex_color(t->color[1]) +
              v * unpack_vertex_color(t->color[2]);
#endif
  return s;
}

// The width of a camera ray's cone at distance t: the spacing of the frame's samples (a pixel, or the jitter cell of
// a path-traced round's strata) seen from the eye, which its texture lookups are filtered to (below) and the glass caustic map is read over
// (kernels/glass_caustics.cl).
inline float primary_cone_width(__global const CameraParams* cam, float t) {
  const float cell = cam->jitter_cell > 0.0f ? cam->jitter_cell : 1.0f;
  if (cam->orthographic) return 2.0f * cam->half_height / (float)cam->height * cell;
  return t * 2.0f * cam->tan_half_fov_y / (float)cam->height * cell;
}

// Texture lookups: base colour and metallic-roughness (HAS_TEXTURES), normal maps, textured emission.
#define TEXTURE_LOOKUPS (HAS_TEXTURES || HAS_NORMAL_MAPS || HAS_EMISSIVE_TEXTURES)

#if TEXTURE_LOOKUPS
#include "srgb_table.h"

inline int wrap_texel(int i, int n, uint mode) {
  if (mode == WRAP_CLAMP) return clamp(i, 0, n - 1);
  if (mode == WRAP_MIRROR) {
    int m = i % (2 * n);
    if (m < 0) m += 2 * n;
    return m < n ? m : 2 * n - 1 - m;
  }
  int m = i % n;
  return m < 0 ? m + n : m;
}

// A texel's RGBA: colour decoded from sRGB, or (data textures such as metallic-roughness) taken as stored.
inline float4 texel_value(__global const uint* texels, TextureInfo info, int x, int y, bool srgb) {
  uint p = texels[info.first_texel + (uint)y * info.width + (uint)x];
  const float to_unit = 1.0f / 255.0f;
  if (!srgb)
    return (float4)((float)(p & 255u), (float)((p >> 8) & 255u), (float)((p >> 16) & 255u), (float)(p >> 24)) * to_unit;
  return (float4)(SRGB_TO_LINEAR[p & 255u], SRGB_TO_LINEAR[(p >> 8) & 255u], SRGB_TO_LINEAR[(p >> 16) & 255u],
                  (float)(p >> 24) * to_unit);
}

// Bilinear (or, as the sampler says, nearest) lookup in one level (`info` describing that level); texture coordinates
// wrap as the sampler says. Colour textures (srgb) are filtered in linear space.
inline float4 sample_level(__global const uint* texels, TextureInfo info, float2 uv, bool srgb) {
  int w = (int)info.width, h = (int)info.height;
  uint ws = texture_wrap_s(info.wrap), wt = texture_wrap_t(info.wrap);
  if (info.wrap & TEXTURE_NEAREST) {
    float nx = floor(uv.x * (float)w), ny = floor(uv.y * (float)h);
    if (!isfinite(nx) || !isfinite(ny) || fabs(nx) > 1e8f || fabs(ny) > 1e8f) nx = ny = 0.0f;
    return texel_value(texels, info, wrap_texel((int)nx, w, ws), wrap_texel((int)ny, h, wt), srgb);
  }
  float fx = uv.x * (float)w - 0.5f, fy = uv.y * (float)h - 0.5f;
  if (!isfinite(fx) || !isfinite(fy) || fabs(fx) > 1e8f || fabs(fy) > 1e8f) fx = fy = 0.0f;
  float x0f = floor(fx), y0f = floor(fy);
  float ax = fx - x0f, ay = fy - y0f;
  int x0 = (int)x0f, y0 = (int)y0f;
  int xa = wrap_texel(x0, w, ws), xb = wrap_texel(x0 + 1, w, ws);
  int ya = wrap_texel(y0, h, wt), yb = wrap_texel(y0 + 1, h, wt);
  float4 top = mix(texel_value(texels, info, xa, ya, srgb), texel_value(texels, info, xb, ya, srgb), ax);
  float4 bottom = mix(texel_value(texels, info, xa, yb, srgb), texel_value(texels, info, xb, yb, srgb), ax);
  return mix(top, bottom, ay);
}

// Mip level `level` of a texture as a TextureInfo of its own: the levels follow each other from first_texel.
inline TextureInfo texture_level(TextureInfo info, uint level) {
  for (uint k = 0; k < level; ++k) {
    info.first_texel += info.width * info.height;
    info.width = texture_level_side(info.width, 1u);
    info.height = texture_level_side(info.height, 1u);
  }
  return info;
}

// A lookup filtered to a footprint 2^uv_width_log2 wide in texture coordinates (a ray cone's: uv_width_log2 below):
// trilinear between the two mip levels whose texels are nearest that width. A footprint below a
// texel (or none: -INFINITY) reads level 0 alone, bilinear, exactly as a lookup without footprint.
inline float4 sample_texture_footprint(__global const TextureInfo* infos, __global const uint* texels, int index,
                                       float2 uv, float uv_width_log2, bool srgb) {
  TextureInfo info = infos[index];
  const uint levels = texture_levels(info.wrap);
  float lod = uv_width_log2 + 0.5f * log2((float)info.width * (float)info.height);
  if (!(lod > 0.0f) || levels <= 1u) return sample_level(texels, info, uv, srgb);
  lod = fmin(lod, (float)(levels - 1u));
  const uint finer = (uint)lod;
  const float f = lod - (float)finer;
  const float4 a = sample_level(texels, texture_level(info, finer), uv, srgb);
  if (f == 0.0f || finer + 1u >= levels) return a;
  return mix(a, sample_level(texels, texture_level(info, finer + 1u), uv, srgb), f);
}

inline float4 sample_texture(__global const TextureInfo* infos, __global const uint* texels, int index, float2 uv) {
  return sample_level(texels, infos[index], uv, true);
}

// log2 of the width, in texture coordinates, that a ray cone `width` wide (world units) covers where it meets the
// triangle along dir: the width over the cosine (the cone's section stretched across the surface), times the
// triangle's texture-coordinate scale sqrt(uv area / world area) (Akenine-Moller et al., "Texture Level of Detail
// Strategies for Real-Time Ray Tracing", 2019). -INFINITY where the triangle has no texture-coordinate area.
inline float uv_width_log2(__global const TriangleShading* t, float width, float3 dir) {
  const float3 v0 = vload3(0, t->v0);
  const float world_area = length(cross(vload3(0, t->v1) - v0, vload3(0, t->v2) - v0));
  const float2 uv0 = vload2(0, t->uv0), d1 = vload2(0, t->uv1) - uv0, d2 = vload2(0, t->uv2) - uv0;
  const float uv_area = fabs(d1.x * d2.y - d2.x * d1.y);
  const float cos_theta = fmax(fabs(dot(dir, vload3(0, t->geometric_normal))), 0.05f);  // grazing: 20x at most
  if (!(world_area > 0.0f) || !(uv_area > 0.0f) || !(width > 0.0f)) return -INFINITY;
  return log2(width / cos_theta) + 0.5f * log2(uv_area / world_area);
}
#endif

#if HAS_NORMAL_MAPS
// The normal map's normal at s on triangle prim (barycentrics u, v), unit, in world space, on the side the
// interpolated normal faces (glTF: n = normalize(T x + B y + N z) with (x, y, z) = (2 rgb - 1) * (scale, scale, 1) and
// B = cross(N, T) * w). The vertices' tangents are interpolated and made orthogonal to N; one along N takes any
// frame. s's own normal where its material has no map, or where the triangle has none (w = 0: the loader found no
// texture coordinates or no gradient of them).
inline float3 bent_normal(__global const float4* tangents, __global const TextureInfo* textures,
                          __global const uint* texels, const SurfacePoint* s, int prim, float u, float v, int texture,
                          float scale) {
  const float3 n = s->shading_normal;
  if (texture < 0 || tangents[3 * prim].w == 0.0f) return n;  // w = 0: no map on this triangle
  const float4 tw = (1.0f - u - v) * tangents[3 * prim] + u * tangents[3 * prim + 1] + v * tangents[3 * prim + 2];
  float3 t = tw.xyz - dot(tw.xyz, n) * n, b;
  const float t_length = length(t);
  if (t_length > 1e-6f) {
    t /= t_length;
    b = cross(n, t) * (tw.w < 0.0f ? -1.0f : 1.0f);
  } else {
    tangent_frame(n, &t, &b);
  }
  const float3 texel = sample_texture_footprint(textures, texels, texture, s->uv, s->uv_width_log2, false).xyz * 2.0f - 1.0f;
  const float3 bent = (texel.x * scale) * t + (texel.y * scale) * b + texel.z * n;
  const float bent_length = length(bent);
  return bent_length > 0.0f && isfinite(bent_length) ? bent / bent_length : n;
}

// The material's normal map's normal at s (bent_normal).
inline float3 mapped_normal(__global const float4* tangents, __global const Material* materials,
                            __global const TextureInfo* textures, __global const uint* texels, const SurfacePoint* s,
                            int prim, float u, float v) {
  __global const Material* m = materials + s->material;
  return bent_normal(tangents, textures, texels, s, prim, u, v, m->normal_texture, m->normal_scale);
}
#endif

#if HAS_EMISSIVE_TEXTURES
// The emission of s's material: its factor times its emissive texture (sRGB) at s.
inline float3 textured_emission(__global const Material* m, __global const TextureInfo* textures,
                                __global const uint* texels, float2 uv, float uv_width_log2) {
  float3 emission = vload3(0, m->emission);
  if (m->emissive_texture >= 0)
    emission *= sample_texture_footprint(textures, texels, m->emissive_texture, uv, uv_width_log2, true).xyz;
  return emission;
}
#endif

// The radiance the front of s emits (the factor, times its texture where it has one).
inline float3 surface_emission(__global const Material* materials, __global const TextureInfo* textures,
                               __global const uint* texels, const SurfacePoint* s) {
#if HAS_EMISSIVE_TEXTURES
  return textured_emission(materials + s->material, textures, texels, s->uv, s->uv_width_log2);
#else
  return vload3(0, materials[s->material].emission);
#endif
}

// The radiance emitter e sends from its point at barycentrics (u, v): its texels' there where its emission is
// textured, else its (uniform) radiance. The light sampler, BRDF samples that land on it and its photons read this.
inline float3 emitter_radiance_at(EmissiveTriangle e, float u, float v, __global const TriangleShading* triangles,
                                  __global const Material* materials, __global const TextureInfo* textures,
                                  __global const uint* texels) {
#if HAS_EMISSIVE_TEXTURES
  if (emitter_textured_triangle(e) >= 0) {
    SurfacePoint at = surface_at(triangles, emitter_textured_triangle(e), u, v);
    return surface_emission(materials, textures, texels, &at);
  }
#endif
  return vload3(0, e.radiance);
}

inline float3 surface_albedo(__global const Material* materials, __global const TextureInfo* textures,
                             __global const uint* texels, const SurfacePoint* s) {
  __global const Material* m = materials + s->material;
  float3 albedo = vload3(0, m->base_color);
#if HAS_TEXTURES
  if (m->base_color_texture >= 0)
    albedo *= sample_texture_footprint(textures, texels, m->base_color_texture, s->uv, s->uv_width_log2, true).xyz;
#endif
#if HAS_VERTEX_COLORS
  albedo *= s->color;
#endif
  return clamp(albedo, 0.0f, 1.0f);
}

// The specular lobe's parameters at a surface point: the material's factors times its metallic-roughness texture
// (glTF: B metallic, G roughness), and the lobe kind they make there.
typedef struct {
  float metallic, roughness, specular;
  int lobe;  // LOBE_*
#if HAS_LAYERS
  SurfaceLayers layers;  // the coat's normal is the hit's (hit_lobe) or the pixel's (kernels/gbuffer.cl)
#endif
} SurfaceLobe;

#if HAS_LAYERS
// The layers of s's material there (factors times textures), and the lobe kind they make with the base's `base`. The
// coat's normal is left as s's interpolated normal: hit_lobe orients it and applies the coat's normal map.
inline int read_layers(__global const Material* m, __global const TextureInfo* textures, __global const uint* texels,
                       const SurfacePoint* s, int base, SurfaceLayers* l) {
  float3 specular_color = vload3(0, m->specular_color), sheen = vload3(0, m->sheen_color);
  float clearcoat = m->clearcoat, coat_roughness = m->clearcoat_roughness, sheen_roughness = m->sheen_roughness;
#if HAS_TEXTURES
  const float2 uv = s->uv;
  const float w = s->uv_width_log2;
  if (m->specular_color_texture >= 0)
    specular_color *= sample_texture_footprint(textures, texels, m->specular_color_texture, uv, w, true).xyz;
  if (m->clearcoat_texture >= 0) clearcoat *= sample_texture_footprint(textures, texels, m->clearcoat_texture, uv, w, false).x;
  if (m->clearcoat_roughness_texture >= 0)
    coat_roughness *= sample_texture_footprint(textures, texels, m->clearcoat_roughness_texture, uv, w, false).y;
  if (m->sheen_color_texture >= 0) sheen *= sample_texture_footprint(textures, texels, m->sheen_color_texture, uv, w, true).xyz;
  if (m->sheen_roughness_texture >= 0)
    sheen_roughness *= sample_texture_footprint(textures, texels, m->sheen_roughness_texture, uv, w, false).w;
#endif
  vstore3(specular_color, 0, l->specular_color);
  l->clearcoat = clearcoat;
  vstore3(s->shading_normal, 0, l->coat_normal);
  l->clearcoat_roughness = coat_roughness;
  vstore3(sheen, 0, l->sheen_color);
  l->sheen_roughness = sheen_roughness;
  return layered_lobe(base, clearcoat, coat_roughness, fmax(sheen.x, fmax(sheen.y, sheen.z)));
}

// No layers: what leaves the base as it is.
inline void no_layers(float3 n, SurfaceLayers* l) {
  vstore3((float3)(1.0f), 0, l->specular_color);
  l->clearcoat = 0.0f;
  vstore3(n, 0, l->coat_normal);
  l->clearcoat_roughness = 1.0f;
  vstore3((float3)(0.0f), 0, l->sheen_color);
  l->sheen_roughness = 1.0f;
}
#endif

inline SurfaceLobe surface_lobe(__global const Material* materials, __global const TextureInfo* textures,
                                __global const uint* texels, const SurfacePoint* s) {
  __global const Material* m = materials + s->material;
  SurfaceLobe l;
  l.metallic = m->metallic;
  l.roughness = m->roughness;
  l.specular = m->specular;
  l.lobe = m->lobe;
#if HAS_TEXTURES
  if (m->lobe != LOBE_NONE && (m->metallic_roughness_texture >= 0 || m->specular_texture >= 0)) {
    if (m->metallic_roughness_texture >= 0) {
      float4 mr =
          sample_texture_footprint(textures, texels, m->metallic_roughness_texture, s->uv, s->uv_width_log2, false);
      l.metallic *= mr.z;
      l.roughness *= mr.y;
    }
    if (m->specular_texture >= 0)  // KHR_materials_specular: the texture's alpha times specularFactor
      l.specular *= sample_texture_footprint(textures, texels, m->specular_texture, s->uv, s->uv_width_log2, false).w;
    l.lobe = material_lobe(l.metallic, l.roughness, l.specular);
    // The HSH table is the material's, at its roughness factor: a lobe whose roughness a texture varies is sampled.
    // (A specular weight varies only the Fresnel terms, which each pixel applies to the table itself.)
    if (l.lobe == LOBE_HSH && m->metallic_roughness_texture >= 0) l.lobe = LOBE_GLOSSY;
  }
#endif
#if HAS_LAYERS
  if (m->layered) l.lobe = read_layers(m, textures, texels, s, material_lobe(l.metallic, l.roughness, l.specular), &l.layers);
  else no_layers(s->shading_normal, &l.layers);
#endif
  return l;
}

// A surface a ray found, oriented toward the ray (surfaces reflect on both sides, as in the G-buffer). Its albedo and
// lobe are read on first use (hit_albedo, hit_lobe): a hit no light reaches never reads its texels, which cost a tenth
// of Sponza's record pass when every hit read them.
typedef struct {
  SurfacePoint s;
  float3 ns, ng, albedo;  // ns: the shading normal (the normal map's, where there is one)
#if HAS_NORMAL_MAPS
  float3 ns_interpolated;  // the interpolated normal, oriented as ns: what the cache weighs records by
#endif
#if HAS_LAYERS
  float3 coat_normal;  // the clearcoat's: its own normal map's, else the interpolated normal (not the base's map)
#endif
  SurfaceLobe lobe;
  int albedo_read, lobe_read;
  HitDesc hit;  // the trace's hit it was built from (a queued path keeps it: kernels/path_queue.h)
} HitSurface;

// What hit_surface reads: the triangles, and for normal maps their tangents, materials and texels.
#define HIT_SURFACE_ARGS                                                                                              \
  __global const TriangleShading *triangles, __global const float4 *tangents, __global const Material *materials, \
      __global const TextureInfo *textures, __global const uint *texels
#define HIT_SURFACE triangles, tangents, materials, textures, texels

// The surface a ray along dir landed on (triangle prim at barycentrics u, v), its normals turned to face the ray.
// `width`: the ray cone's width there (world units), which filters its texture lookups; 0: texel-sized lookups.
inline HitSurface hit_surface(HIT_SURFACE_ARGS, int prim, float u, float v, float3 dir, float width) {
  HitSurface h;
  h.s = surface_at(triangles, prim, u, v);
#if TEXTURE_LOOKUPS
  if (width > 0.0f) h.s.uv_width_log2 = uv_width_log2(triangles + prim, width, dir);
#endif
  h.hit.t = 0.0f;  // not known here, and not needed to build the surface again
  h.hit.u = u;
  h.hit.v = v;
  h.hit.prim = prim;
  bool back = dot(h.s.geometric_normal, dir) > 0.0f;
  h.ng = back ? -h.s.geometric_normal : h.s.geometric_normal;
  h.ns = back ? -h.s.shading_normal : h.s.shading_normal;
  if (dot(h.ns, h.ng) <= 0.0f) h.ns = h.ng;  // inconsistent vertex normals: trust the geometry
#if HAS_LAYERS
  h.coat_normal = h.ns;
#if HAS_NORMAL_MAPS
  __global const Material* coated = materials + h.s.material;
  if (coated->layered && coated->clearcoat > 0.0f && coated->clearcoat_normal_texture >= 0) {
    float3 bent = bent_normal(tangents, textures, texels, &h.s, prim, u, v, coated->clearcoat_normal_texture,
                              coated->clearcoat_normal_scale);
    if (back) bent = -bent;
    if (dot(bent, h.ng) > 0.0f) h.coat_normal = bent;
  }
#endif
#endif
#if HAS_NORMAL_MAPS
  h.ns_interpolated = h.ns;
  if (materials[h.s.material].normal_texture >= 0) {
    float3 bent = mapped_normal(tangents, materials, textures, texels, &h.s, prim, u, v);
    if (back) bent = -bent;
    if (dot(bent, h.ng) > 0.0f) h.ns = bent;  // a map that bends below the surface: the interpolated normal shades
  }
#endif
  h.albedo_read = h.lobe_read = 0;
  return h;
}

// The surface a photon along dir landed on (kernels/light_guide.cl): as hit_surface, but shaded with its interpolated
// normal alone (the coat's too), a normal that faces away from the photon replaced by the geometric one, and texel-sized
// lookups. Kept beside hit_surface so that a field HitSurface gains is set in both.
inline HitSurface photon_hit_surface(__global const TriangleShading* triangles, int prim, float u, float v,
                                     float3 dir) {
  HitSurface h;
  h.s = surface_at(triangles, prim, u, v);
  h.ng = dot(h.s.geometric_normal, dir) > 0.0f ? -h.s.geometric_normal : h.s.geometric_normal;
  h.ns = dot(h.s.shading_normal, h.ng) > 0.0f ? h.s.shading_normal : h.ng;
#if HAS_NORMAL_MAPS
  h.ns_interpolated = h.ns;
#endif
#if HAS_LAYERS
  h.coat_normal = h.ns;
#endif
  h.albedo_read = h.lobe_read = 0;
  return h;
}

inline float3 hit_albedo(__global const Material* materials, __global const TextureInfo* textures,
                         __global const uint* texels, HitSurface* h) {
  if (!h->albedo_read) {
    h->albedo = surface_albedo(materials, textures, texels, &h->s);
    h->albedo_read = 1;
  }
  return h->albedo;
}

inline SurfaceLobe hit_lobe(__global const Material* materials, __global const TextureInfo* textures,
                            __global const uint* texels, HitSurface* h) {
  if (!h->lobe_read) {
    h->lobe = surface_lobe(materials, textures, texels, &h->s);
#if HAS_LAYERS
    vstore3(h->coat_normal, 0, h->lobe.layers.coat_normal);
#endif
    h->lobe_read = 1;
  }
  return h->lobe;
}

// The lobe kind at a hit: the material's, unless its metallic-roughness or specular texture may change it there.
inline int hit_lobe_kind(__global const Material* materials, __global const TextureInfo* textures,
                         __global const uint* texels, HitSurface* h) {
  __global const Material* m = materials + h->s.material;
#if HAS_TEXTURES
  if (m->lobe != LOBE_NONE && (m->metallic_roughness_texture >= 0 || m->specular_texture >= 0))
    return hit_lobe(materials, textures, texels, h).lobe;
#endif
#if HAS_LAYERS
  if (m->layered) return hit_lobe(materials, textures, texels, h).lobe;
#endif
  return m->lobe;
}

#endif
