// The one BRDF of the renderer: glTF 2.0's metallic-roughness model (specification, appendix B), a Lambertian base
// and a GGX microfacet lobe with height-correlated Smith masking-shadowing and Schlick's Fresnel:
//   f = (1 - metallic) * dielectric + metallic * metal,
//   dielectric = (1 - E_d(n.v)) * base / pi + F_d(v.h) * spec,   F_d(c) = specular * (0.04 + 0.96 (1 - c)^5),
//   metal = (base + (1 - base) (1 - v.h)^5) * spec,    spec = D(h) V(l, v),
//   D = a^2 / (pi ((n.h)^2 (a^2 - 1) + 1)^2),          a = roughness^2,
//   V = G2 / (4 n.l n.v) = 0.5 / (n.l sqrt((n.v)^2 (1 - a^2) + a^2) + n.v sqrt((n.l)^2 (1 - a^2) + a^2)).
// The one departure from appendix B: the diffuse base is weighted by 1 - E_d(n.v), one less the dielectric lobe's
// directional albedo toward the view (what the lobe reflects of uniform light), not by 1 - F_d(v.h) per microfacet.
// Appendix B's per-microfacet weight reflects more than it receives at grazing view (a white dielectric's albedo
// reaches 1.37 at cos 0.17, tests/brdf_test.cpp); 1 - E_d keeps the white furnace at 1 exactly (the base takes what
// the lobe leaves) and makes the diffuse part a constant times base / pi at each pixel, which an irradiance cache
// needs. A smooth lobe's E_d is its Fresnel F_d(n.v); a rough lobe's is far below it at grazing view, where
// 1 - F_d(n.v) (rcsplat's weight before) darkened rough surfaces by up to 70% against appendix B (docs/NOTES.md
// "Issue 41: a dielectric as bright as glTF means").
// `specular` is KHR_materials_specular's factor (1 by default); 0 with metallic 0 leaves exactly base / pi, the
// Lambertian surfaces rcsplat shaded before. Vectors are in the local frame of the shading normal (+z).
// Sampling mixes a cosine lobe and GGX's distribution of visible normals (Heitz 2018), chosen by their estimated
// weights; brdf_pdf is the mixture's density, so callers weigh light samples against it (multiple importance).
#ifndef RCSPLAT_BRDF_H
#define RCSPLAT_BRDF_H
#include "host_device.h"
#include "specular_albedo_values.h"

#define DIELECTRIC_F0 0.04f
// a = roughness^2 is kept above this: a smaller lobe is a near-mirror whose peak float cannot hold (D ~ 1 / a^2).
#define MIN_GGX_ALPHA 1.0e-3f

typedef struct {
  float3 base_color;
  float metallic;
  float alpha;     // GGX a = roughness^2, at least MIN_GGX_ALPHA
  float specular;  // weight of the dielectric's specular layer, 0..1
#if HAS_LAYERS
  // The layers (kernels/brdf_layers.h): the dielectric's F0 (DIELECTRIC_F0 times KHR_materials_specular's colour, at
  // most 1), the coat's weight (0: none), GGX a and frame (its normal as +z, local to the shading frame), the sheen's
  // colour (0: none) and alpha.
  float3 f0;
  float clearcoat, coat_alpha;
  float3 coat_t, coat_b, coat_n;
  float3 sheen;
  float sheen_alpha;
#endif
} BrdfInputs;

inline BrdfInputs brdf_inputs(float3 base_color, float metallic, float roughness, float specular) {
  BrdfInputs in;
  in.base_color = base_color;
  in.metallic = clamp(metallic, 0.0f, 1.0f);
  in.alpha = fmax(roughness * roughness, MIN_GGX_ALPHA);
  in.specular = clamp(specular, 0.0f, 1.0f);
#if HAS_LAYERS
  in.f0 = (float3)(DIELECTRIC_F0);
  in.clearcoat = 0.0f;
  in.coat_alpha = 1.0f;
  in.coat_t = (float3)(1.0f, 0.0f, 0.0f);
  in.coat_b = (float3)(0.0f, 1.0f, 0.0f);
  in.coat_n = (float3)(0.0f, 0.0f, 1.0f);
  in.sheen = (float3)(0.0f);
  in.sheen_alpha = 1.0f;
#endif
  return in;
}

inline float schlick_weight(float v_dot_h) {
  float m = clamp(1.0f - v_dot_h, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}

// D for the unit half vector h. (n.h)^2 (a^2 - 1) + 1 is written as sin^2 + cos^2 a^2 with sin^2 = h.x^2 + h.y^2: the
// textbook form cancels near the peak of a sharp lobe, where D is largest (1% error at roughness 0.05 in float).
inline float ggx_d(float3 h, float a2) {
  float d = h.x * h.x + h.y * h.y + h.z * h.z * a2;
  return a2 / (RC_PI * d * d);
}

// Smith's G1 for GGX (the masking of one direction).
inline float ggx_g1(float n_dot_v, float a2) {
  return 2.0f * n_dot_v / (n_dot_v + sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v));
}

// V = G2 / (4 n.l n.v), height-correlated.
inline float ggx_visibility(float n_dot_l, float n_dot_v, float a2) {
  float gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2);
  float gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2);
  return 0.5f / (gv + gl);
}

// The specular lobe's directional albedo terms (T0, T1) toward a view at cos_o (kernels/specular_albedo_values.h: a
// lobe whose Fresnel is c0 + c1 (1 - v.h)^5 reflects c0 T0 + c1 T1 of uniform light), read bilinearly by cos_o and
// roughness = sqrt(a).
inline float2 ggx_albedo_split(float alpha, float cos_o) {
  const int n = SPECULAR_ALBEDO_TABLE_SIZE;
  float x = clamp(cos_o, 0.0f, 1.0f) * (float)(n - 1), y = clamp(sqrt(alpha), 0.0f, 1.0f) * (float)(n - 1);
  int x0 = min((int)x, n - 2), y0 = min((int)y, n - 2);
  float fx = x - (float)x0, fy = y - (float)y0;
  __constant const float* row0 = specular_albedo_values + 2 * (y0 * n + x0);
  __constant const float* row1 = row0 + 2 * n;
  float2 bottom = mix((float2)(row0[0], row0[1]), (float2)(row0[2], row0[3]), fx);
  float2 top = mix((float2)(row1[0], row1[1]), (float2)(row1[2], row1[3]), fx);
  return mix(bottom, top, fy);
}
inline float2 specular_albedo_split(BrdfInputs in, float cos_o) { return ggx_albedo_split(in.alpha, cos_o); }

// The dielectric's diffuse weight 1 - E_d (without the (1 - metallic) factor), from the lobe's albedo terms toward
// the view (specular_albedo_split): what its specular layer leaves.
inline float diffuse_weight_from_terms(BrdfInputs in, float2 terms) {
#if HAS_LAYERS
  // KHR_materials_specular: a coloured F0 leaves the base what its strongest channel leaves (the extension's max3).
  const float3 lobe = in.f0 * terms.x + ((float3)(1.0f) - in.f0) * terms.y;
  return 1.0f - in.specular * fmax(lobe.x, fmax(lobe.y, lobe.z));
#else
  return 1.0f - in.specular * (DIELECTRIC_F0 * terms.x + (1.0f - DIELECTRIC_F0) * terms.y);
#endif
}

inline float brdf_diffuse_weight(BrdfInputs in, float n_dot_v) {
  return diffuse_weight_from_terms(in, specular_albedo_split(in, n_dot_v));
}

// The specular lobe's Fresnel colour is c0 + c1 (1 - v.h)^5: the dielectric layer's and the metal's Schlick terms,
// mixed by metallic. Split so that the lobe's albedo can be tabulated once for all materials (kernels/brdf_frame.h).
inline void specular_fresnel_terms(BrdfInputs in, float3* c0, float3* c1) {
#if HAS_LAYERS
  *c0 = (1.0f - in.metallic) * in.specular * in.f0 + in.metallic * in.base_color;
  *c1 = (1.0f - in.metallic) * in.specular * ((float3)(1.0f) - in.f0) + in.metallic * ((float3)(1.0f) - in.base_color);
#else
  *c0 = (float3)((1.0f - in.metallic) * in.specular * DIELECTRIC_F0) + in.metallic * in.base_color;
  *c1 = (float3)((1.0f - in.metallic) * in.specular * (1.0f - DIELECTRIC_F0)) +
        in.metallic * ((float3)(1.0f) - in.base_color);
#endif
}

inline float3 brdf_specular_fresnel(BrdfInputs in, float v_dot_h) {
  float3 c0, c1;
  specular_fresnel_terms(in, &c0, &c1);
  return c0 + c1 * schlick_weight(v_dot_h);
}

// G2(l, v) / G1(v) = 4 n.l n.v V / G1(v): the weight of a reflection drawn through the visible normals, without F.
inline float ggx_g2_over_g1(float n_dot_l, float n_dot_v, float a2) {
  return 4.0f * n_dot_l * n_dot_v * ggx_visibility(n_dot_l, n_dot_v, a2) / ggx_g1(n_dot_v, a2);
}

// The base's diffuse part alone: (1 - metallic) (1 - E_d(n.v)) base / pi, a constant over wi.
inline float3 base_eval_diffuse(BrdfInputs in, float n_dot_v) {
  return ((1.0f - in.metallic) * brdf_diffuse_weight(in, n_dot_v) * RC_INV_PI) * in.base_color;
}

// The base's specular lobe alone, F D V; zero unless both directions lie above the surface.
inline float3 base_eval_specular(BrdfInputs in, float3 wo, float3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
  float3 h = normalize(wo + wi);
  float a2 = in.alpha * in.alpha;
  return brdf_specular_fresnel(in, fmax(dot(wo, h), 0.0f)) * (ggx_d(h, a2) * ggx_visibility(wi.z, wo.z, a2));
}

// The base's specular lobe's directional albedo toward wo, c0 T0 + c1 T1 (the table, kernels/brdf.h).
inline float3 base_specular_albedo(BrdfInputs in, float3 wo) {
  float2 t = specular_albedo_split(in, wo.z);
  float3 c0, c1;
  specular_fresnel_terms(in, &c0, &c1);
  return c0 * t.x + c1 * t.y;
}

// f_specular cos(wi) / (density of sampling wi through the visible normals) = F G2 / G1(wo), for wi the reflection of
// wo about a visible normal: the weight of one sample of the base's lobe alone.
inline float3 brdf_specular_weight(BrdfInputs in, float3 wo, float3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
  float3 h = normalize(wo + wi);
  return brdf_specular_fresnel(in, fmax(dot(wo, h), 0.0f)) * ggx_g2_over_g1(wi.z, wo.z, in.alpha * in.alpha);
}

// Probability of sampling the GGX lobe rather than the cosine lobe, from the lobes' weights seen from wo, estimated
// with Schlick's Fresnel of the view: any split keeps the estimate unbiased (brdf_pdf uses the same), and this one
// costs no table read (brdf_sample would read it three times a sample, in the kernels that trace paths).
// The base's specular lobe's and diffuse part's weights toward wo, estimated with Schlick's Fresnel of the view for a
// dielectric F0 of f0 (grey): what brdf_specular_probability and the layers' mixture (kernels/brdf_layers.h) share
// their samples by.
inline void base_lobe_estimates(BrdfInputs in, float3 wo, float f0, float* spec, float* diffuse) {
  float fw = schlick_weight(wo.z);
  float gray = (in.base_color.x + in.base_color.y + in.base_color.z) * (1.0f / 3.0f);
  float fd = in.specular * (f0 + (1.0f - f0) * fw);
  *spec = (1.0f - in.metallic) * fd + in.metallic * (gray + (1.0f - gray) * fw);
  *diffuse = (1.0f - in.metallic) * (1.0f - fd) * gray;
}

inline float brdf_specular_probability(BrdfInputs in, float3 wo) {
  float spec, diffuse;
  base_lobe_estimates(in, wo, DIELECTRIC_F0, &spec, &diffuse);
  if (spec <= 0.0f) return 0.0f;
  if (diffuse <= 0.0f) return 1.0f;
  return clamp(spec / (spec + diffuse), 0.1f, 0.9f);  // neither lobe starved where both contribute
}

// The density (solid angle) of reflecting wo about a visible normal of a GGX lobe of alpha: D(h) G1(wo) / (4 wo.z).
inline float ggx_reflection_pdf(float alpha, float3 wo, float3 wi) {
  float a2 = alpha * alpha;
  return ggx_d(normalize(wo + wi), a2) * ggx_g1(wo.z, a2) / (4.0f * wo.z);
}

// A direction drawn from the visible normals of the GGX lobe (Heitz 2018), for uniform (u1, u2).
inline float3 ggx_sample_visible_normal(float3 wo, float alpha, float u1, float u2) {
  float3 vh = normalize((float3)(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  float3 t1 = len2 > 0.0f ? (float3)(-vh.y, vh.x, 0.0f) * rsqrt(len2) : (float3)(1.0f, 0.0f, 0.0f);
  float3 t2 = cross(vh, t1);
  float r = sqrt(u1), phi = 2.0f * RC_PI * u2;
  float p1 = r * cos(phi), p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(fmax(1.0f - p1 * p1, 0.0f)) + s * p2;
  float3 nh = p1 * t1 + p2 * t2 + sqrt(fmax(1.0f - p1 * p1 - p2 * p2, 0.0f)) * vh;
  return normalize((float3)(alpha * nh.x, alpha * nh.y, fmax(nh.z, 0.0f)));
}

// The reflection of wo about a normal drawn from the lobe's visible normals (ggx_sample_visible_normal), for uniform
// (u1, u2): its weight f_specular cos / pdf is brdf_specular_weight.
inline float3 ggx_sample_reflection(float3 wo, float alpha, float u1, float u2) {
  float3 h = ggx_sample_visible_normal(wo, alpha, u1, u2);
  return 2.0f * dot(wo, h) * h - wo;
}

// A cosine-weighted direction about +z for uniform (u1, u2).
inline float3 cosine_local_direction(float u1, float u2) {
  float sin_t = sqrt(u1), phi = 2.0f * RC_PI * u2;
  return (float3)(cos(phi) * sin_t, sin(phi) * sin_t, sqrt(fmax(1.0f - u1, 0.0f)));
}

// Clearcoat, sheen and specular colour over the base (HAS_LAYERS; nothing without it).
#include "brdf_layers.h"

// The BRDF's part that is constant over wi, for a view wo: the base's diffuse part, under the layers where there are
// any. The irradiance cache is exact for it.
inline float3 brdf_eval_diffuse(BrdfInputs in, float3 wo) {
#if HAS_LAYERS
  if (has_layer_lobes(in)) return layers_base_share(in, wo) * base_eval_diffuse(in, wo.z);
#endif
  return base_eval_diffuse(in, wo.z);
}

// The BRDF's lobes: the base's specular lobe, and the coat's and sheen's where there are layers. A surface without a
// coat or sheen takes the base's code alone in every function below, so that it keeps its bits in a scene with layers.
inline float3 brdf_eval_specular(BrdfInputs in, float3 wo, float3 wi) {
#if HAS_LAYERS
  if (has_layer_lobes(in)) return layered_eval_lobes(in, wo, wi);
#endif
  return base_eval_specular(in, wo, wi);
}

// f(wo, wi), both in the local frame; zero unless both lie above the surface.
inline float3 brdf_eval(BrdfInputs in, float3 wo, float3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
  return brdf_eval_diffuse(in, wo) + brdf_eval_specular(in, wo, wi);
}

// The lobes' directional albedo toward wo: what they reflect of light even over the hemisphere.
inline float3 lobes_albedo(BrdfInputs in, float3 wo) {
#if HAS_LAYERS
  return layered_lobes_albedo(in, wo);
#else
  return base_specular_albedo(in, wo);
#endif
}

// Irradiance e whose directions are not known, reflected toward wo by a surface of kind `lobe` (LOBE_*): the diffuse
// part exactly, and a rough lobe's albedo times e / pi (the light taken as even over directions, docs/NOTES.md
// "Material kinds"). A sharper lobe reflects none of it here: the caller samples that lobe itself.
inline float3 irradiance_reflected(BrdfInputs in, int lobe, float3 wo, float3 e) {
  float3 l = brdf_eval_diffuse(in, wo) * e;
  if (lobe == LOBE_ROUGH) l += lobes_albedo(in, wo) * RC_INV_PI * e;
  return l;
}

// Density of brdf_sample's directions (solid angle) at wi.
inline float brdf_pdf(BrdfInputs in, float3 wo, float3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
#if HAS_LAYERS
  if (has_layer_lobes(in)) return layered_pdf(in, wo, wi, true);
#endif
  float p_spec = brdf_specular_probability(in, wo);
  float pdf = (1.0f - p_spec) * wi.z * RC_INV_PI;
  if (p_spec > 0.0f) {
    float3 h = normalize(wo + wi);
    float a2 = in.alpha * in.alpha;
    // Visible normals: D(h) G1(wo) (wo.h) / wo.z, times the reflection's Jacobian 1 / (4 wo.h).
    pdf += p_spec * ggx_d(h, a2) * ggx_g1(wo.z, a2) / (4.0f * wo.z);
  }
  return pdf;
}

// Draws wi for wo from (u_lobe, u1, u2). Returns f cos(wi) / pdf, or zero when the direction falls below the surface;
// *pdf is brdf_pdf(wo, wi).
inline float3 brdf_sample(BrdfInputs in, float3 wo, float u_lobe, float u1, float u2, float3* wi, float* pdf) {
  *pdf = 0.0f;
  if (wo.z <= 0.0f) return (float3)(0.0f);
#if HAS_LAYERS
  if (has_layer_lobes(in)) *wi = layered_sample(in, wo, true, u_lobe, u1, u2);
  else
#endif
  if (u_lobe < brdf_specular_probability(in, wo)) {
    *wi = ggx_sample_reflection(wo, in.alpha, u1, u2);
  } else {
    *wi = cosine_local_direction(u1, u2);
  }
  if (wi->z <= 0.0f) return (float3)(0.0f);
  *pdf = brdf_pdf(in, wo, *wi);
  if (!(*pdf > 0.0f)) return (float3)(0.0f);
  return brdf_eval(in, wo, *wi) * (wi->z / *pdf);
}

// The lobes alone (brdf_eval_specular), sampled where a pass estimates their light per pixel (kernels/glossy.cl) or
// follows a sharp lobe (caustic photons, the environment's smooth part): the base's visible normals, and with layers
// a mixture of them, the coat's and a cosine lobe for the sheen (u_lobe chooses; unused without layers).
inline float3 lobes_sample(BrdfInputs in, float3 wo, float u_lobe, float u1, float u2) {
#if HAS_LAYERS
  if (has_layer_lobes(in)) return layered_sample(in, wo, false, u_lobe, u1, u2);
#endif
  return ggx_sample_reflection(wo, in.alpha, u1, u2);
}

// The density of lobes_sample at wi.
inline float lobes_pdf(BrdfInputs in, float3 wo, float3 wi) {
#if HAS_LAYERS
  if (has_layer_lobes(in)) return wo.z > 0.0f && wi.z > 0.0f ? layered_pdf(in, wo, wi, false) : 0.0f;
#endif
  return ggx_reflection_pdf(in.alpha, wo, wi);
}

// The weight of a lobes_sample drawn from `from` toward `to` for light that travels the other way (a photon arriving
// along -from and leaving along to): f_lobes(to, from) cos(to) / pdf. Without a coat or sheen the lobe is symmetric and
// this is lobes_weight; the layers' weights follow the view, here `to`.
inline float3 lobes_adjoint_weight(BrdfInputs in, float3 from, float3 to) {
#if HAS_LAYERS
  if (has_layer_lobes(in)) {
    const float pdf = lobes_pdf(in, from, to);
    return pdf > 0.0f && to.z > 0.0f ? brdf_eval_specular(in, to, from) * (to.z / pdf) : (float3)(0.0f);
  }
#endif
  return brdf_specular_weight(in, from, to);
}

// The weight of one lobes_sample: f_lobes cos / pdf (F G2 / G1 without layers).
inline float3 lobes_weight(BrdfInputs in, float3 wo, float3 wi) {
#if HAS_LAYERS
  if (has_layer_lobes(in)) {
    const float pdf = lobes_pdf(in, wo, wi);
    return pdf > 0.0f ? brdf_eval_specular(in, wo, wi) * (wi.z / pdf) : (float3)(0.0f);
  }
#endif
  return brdf_specular_weight(in, wo, wi);
}

#endif
