// The layers glTF's extensions put over the metallic-roughness base (kernels/brdf.h), compiled only for scenes that have
// them (HAS_LAYERS); docs/ALGORITHM.md section 13 has the model and where it departs from the extensions' texts.
//   KHR_materials_specular's colour: the dielectric's F0 is DIELECTRIC_F0 times the colour (at most 1), and the
//   diffuse base keeps what the strongest channel's lobe leaves (kernels/brdf.h diffuse_weight_from_terms).
//   KHR_materials_sheen: f_sheen = sheen_colour D_charlie(h) V_charlie(o, i), over the base dimmed by
//   1 - max3(sheen_colour) E(n.v), E the lobe's directional albedo (kernels/sheen_albedo_values.h) at the view only
//   (the extension's simpler form: the base's diffuse part stays a constant over wi, which the irradiance cache needs).
//   KHR_materials_clearcoat: a GGX lobe D V of its own roughness and normal, weighed by clearcoat F_c(n_c.v) with
//   F_c Schlick's Fresnel for ior 1.5 at the view, over everything beneath weighed by 1 - clearcoat F_c(n_c.v).
// So f = (1 - c) [sheen D V + s (diffuse + specular)] + c D_coat V_coat, with c = clearcoat F_c(n_c.v) and
// s = 1 - max3(sheen) E(n.v): the weights depend on the view alone.
#ifndef RCSPLAT_BRDF_LAYERS_H
#define RCSPLAT_BRDF_LAYERS_H
#include "sheen_albedo_values.h"

#if HAS_LAYERS
inline float max3(float3 c) { return fmax(c.x, fmax(c.y, c.z)); }

// Whether a coat or a sheen adds a lobe (a specular colour alone tints the base's).
inline bool has_layer_lobes(BrdfInputs in) { return in.clearcoat > 0.0f || max3(in.sheen) > 0.0f; }

// A vector of the shading frame in the coat's frame (its normal as +z).
inline float3 to_coat(BrdfInputs in, float3 v) { return (float3)(dot(v, in.coat_t), dot(v, in.coat_b), dot(v, in.coat_n)); }
inline float3 from_coat(BrdfInputs in, float3 v) { return v.x * in.coat_t + v.y * in.coat_b + v.z * in.coat_n; }

// The coat's share of the light toward wo: clearcoat F_c(n_c.wo), Schlick's Fresnel at ior 1.5 (F0 0.04).
inline float coat_view_weight(BrdfInputs in, float3 wo) {
  if (!(in.clearcoat > 0.0f)) return 0.0f;
  const float c = clamp(dot(wo, in.coat_n), 0.0f, 1.0f);
  return in.clearcoat * (DIELECTRIC_F0 + (1.0f - DIELECTRIC_F0) * schlick_weight(c));
}

// The sheen lobe's directional albedo E (sheen colour 1) toward a view at cos_o, read bilinearly by cos_o and
// roughness = sqrt(alpha). The Charlie lobe reflects more than it receives at grazing views of the smoothest sheens
// (E reaches 5 at roughness 0): E is taken as at most 1, so that the layers beneath never go negative.
inline float sheen_albedo(float alpha, float cos_o) {
  const int n = SHEEN_ALBEDO_TABLE_SIZE;
  float x = clamp(cos_o, 0.0f, 1.0f) * (float)(n - 1), y = clamp(sqrt(alpha), 0.0f, 1.0f) * (float)(n - 1);
  int x0 = min((int)x, n - 2), y0 = min((int)y, n - 2);
  float fx = x - (float)x0, fy = y - (float)y0;
  __constant const float* row0 = sheen_albedo_values + y0 * n + x0;
  __constant const float* row1 = row0 + n;
  return fmin(mix(mix(row0[0], row0[1], fx), mix(row1[0], row1[1], fx), fy), 1.0f);
}

// What the sheen reflects toward wo of light even over the hemisphere (colour times E; 0 without a sheen).
inline float3 sheen_view_albedo(BrdfInputs in, float3 wo) {
  if (!(max3(in.sheen) > 0.0f)) return (float3)(0.0f);
  return in.sheen * sheen_albedo(in.sheen_alpha, wo.z);
}

// What the layers leave to the base toward wo: (1 - clearcoat F_c) (1 - max3(sheen) E).
inline float layers_base_share(BrdfInputs in, float3 wo) {
  return (1.0f - coat_view_weight(in, wo)) * (1.0f - max3(sheen_view_albedo(in, wo)));
}

// The Charlie visibility's Lambda, Estevez and Kulla's fit (the extension's text).
inline float sheen_fitted_l(float x, float alpha) {
  const float t = (1.0f - alpha) * (1.0f - alpha);
  const float a = mix(21.5473f, 25.3245f, t), b = mix(3.82987f, 3.32435f, t), c = mix(0.19823f, 0.16801f, t);
  const float d = mix(-1.97760f, -1.27393f, t), e = mix(-4.32054f, -4.85967f, t);
  return a / (1.0f + b * pow(x, c)) + d * x + e;
}
inline float sheen_lambda(float cos_t, float alpha) {
  return cos_t < 0.5f ? exp(sheen_fitted_l(cos_t, alpha))
                      : exp(2.0f * sheen_fitted_l(0.5f, alpha) - sheen_fitted_l(1.0f - cos_t, alpha));
}

// The sheen lobe: colour D_charlie V_charlie; zero unless both directions lie above the surface.
inline float3 sheen_eval(BrdfInputs in, float3 wo, float3 wi) {
  if (!(max3(in.sheen) > 0.0f) || wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
  const float3 h = normalize(wo + wi);
  const float sin2h = fmax(h.x * h.x + h.y * h.y, 0.0f), inv_alpha = 1.0f / in.sheen_alpha;
  const float d = (2.0f + inv_alpha) * pow(sin2h, 0.5f * inv_alpha) * (0.5f * RC_INV_PI);
  const float v = 1.0f / ((1.0f + sheen_lambda(wo.z, in.sheen_alpha) + sheen_lambda(wi.z, in.sheen_alpha)) *
                          (4.0f * wo.z * wi.z));
  return in.sheen * (d * v);
}

// The coat's lobe without its Fresnel weight: D V in the coat's frame; zero unless both directions lie above the coat.
inline float coat_eval(BrdfInputs in, float3 wo, float3 wi) {
  if (!(in.clearcoat > 0.0f)) return 0.0f;
  const float3 o = to_coat(in, wo), i = to_coat(in, wi);
  if (o.z <= 0.0f || i.z <= 0.0f) return 0.0f;
  const float a2 = in.coat_alpha * in.coat_alpha;
  return ggx_d(normalize(o + i), a2) * ggx_visibility(i.z, o.z, a2);
}

// The lobes of the layered BRDF (everything but the base's diffuse part).
inline float3 layered_eval_lobes(BrdfInputs in, float3 wo, float3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
  const float coat = coat_view_weight(in, wo);
  return layers_base_share(in, wo) * base_eval_specular(in, wo, wi) + (1.0f - coat) * sheen_eval(in, wo, wi) +
         (float3)(coat * coat_eval(in, wo, wi));
}

// The layers' own lobes' directional albedo toward wo: the sheen's E and the coat's T0 (the GGX table's term for a
// Fresnel of 1) at its own roughness and angle, the sheen under the coat. layered_lobes_albedo adds the base's lobe
// (kernels/brdf.h) under both.
inline float3 layers_own_albedo(BrdfInputs in, float3 wo) {
  const float coat = coat_view_weight(in, wo);
  float3 albedo = (1.0f - coat) * sheen_view_albedo(in, wo);
  if (coat > 0.0f) albedo += (float3)(coat * ggx_albedo_split(in.coat_alpha, dot(wo, in.coat_n)).x);
  return albedo;
}

inline float3 layered_lobes_albedo(BrdfInputs in, float3 wo) {
  if (!has_layer_lobes(in)) return base_specular_albedo(in, wo);
  return layers_base_share(in, wo) * base_specular_albedo(in, wo) + layers_own_albedo(in, wo);
}

// How a layered BRDF's samples are shared between a cosine lobe (the diffuse base and the sheen), the base's GGX
// lobe and the coat's, in proportion to their estimated weights toward wo (as brdf_specular_probability estimates
// them), none below a tenth where it contributes; with_diffuse 0: the lobes alone (the sheen keeps the cosine lobe).
typedef struct {
  float base, coat, cosine;
} LobeShares;

inline LobeShares layered_lobe_shares(BrdfInputs in, float3 wo, bool with_diffuse) {
  float base_spec, base_diffuse;
  base_lobe_estimates(in, wo, (in.f0.x + in.f0.y + in.f0.z) * (1.0f / 3.0f), &base_spec, &base_diffuse);
  const float coat = coat_view_weight(in, wo), share = layers_base_share(in, wo);
  float base = share * base_spec;
  float cosine = (1.0f - coat) * max3(sheen_view_albedo(in, wo)) + (with_diffuse ? share * base_diffuse : 0.0f);
  float coat_share = coat;
  const float total = base + cosine + coat_share;
  LobeShares p;
  if (!(total > 0.0f)) {
    p.base = 0.0f;
    p.coat = 0.0f;
    p.cosine = 1.0f;
    return p;
  }
  base = base > 0.0f ? fmax(base / total, 0.1f) : 0.0f;
  cosine = cosine > 0.0f ? fmax(cosine / total, 0.1f) : 0.0f;
  coat_share = coat_share > 0.0f ? fmax(coat_share / total, 0.1f) : 0.0f;
  const float sum = base + cosine + coat_share;
  p.base = base / sum;
  p.coat = coat_share / sum;
  p.cosine = cosine / sum;
  return p;
}

// The density of layered_sample's directions at wi (both above the surface).
inline float layered_pdf(BrdfInputs in, float3 wo, float3 wi, bool with_diffuse) {
  const LobeShares p = layered_lobe_shares(in, wo, with_diffuse);
  float pdf = p.cosine * wi.z * RC_INV_PI;
  if (p.base > 0.0f) pdf += p.base * ggx_reflection_pdf(in.alpha, wo, wi);
  if (p.coat > 0.0f) {
    const float3 o = to_coat(in, wo), i = to_coat(in, wi);
    if (o.z > 0.0f && i.z > 0.0f) pdf += p.coat * ggx_reflection_pdf(in.coat_alpha, o, i);
  }
  return pdf;
}

// A direction from the mixture of layered_lobe_shares: u_lobe chooses the lobe, (u1, u2) place the direction in it.
inline float3 layered_sample(BrdfInputs in, float3 wo, bool with_diffuse, float u_lobe, float u1, float u2) {
  const LobeShares p = layered_lobe_shares(in, wo, with_diffuse);
  if (u_lobe < p.base) return ggx_sample_reflection(wo, in.alpha, u1, u2);
  if (u_lobe < p.base + p.coat) {
    const float3 o = to_coat(in, wo);
    if (o.z <= 0.0f) return (float3)(0.0f, 0.0f, -1.0f);  // the view is behind the coat: no direction
    return from_coat(in, ggx_sample_reflection(o, in.coat_alpha, u1, u2));
  }
  return cosine_local_direction(u1, u2);
}

// The layers at a surface point (SurfaceLayers: world-space coat normal) added to its base BRDF, in the local frame of
// the shading normal n.
inline BrdfInputs with_layers(BrdfInputs in, SurfaceLayers l, float3 n) {
  in.f0 = fmin((float3)(DIELECTRIC_F0) * vload3(0, l.specular_color), (float3)(1.0f));
  in.clearcoat = clamp(l.clearcoat, 0.0f, 1.0f);
  in.coat_alpha = fmax(l.clearcoat_roughness * l.clearcoat_roughness, MIN_GGX_ALPHA);
  if (in.clearcoat > 0.0f) {
    float3 t, b;
    tangent_frame(n, &t, &b);
    const float3 coat_world = vload3(0, l.coat_normal);
    in.coat_n = normalize((float3)(dot(coat_world, t), dot(coat_world, b), dot(coat_world, n)));
    tangent_frame(in.coat_n, &in.coat_t, &in.coat_b);
  }
  in.sheen = clamp(vload3(0, l.sheen_color), 0.0f, 1.0f);
  in.sheen_alpha = fmax(l.sheen_roughness * l.sheen_roughness, SHEEN_MIN_ALPHA);
  return in;
}
#endif

#endif
