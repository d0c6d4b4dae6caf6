// An independent double-precision model of the layers over glTF's base (kernels/brdf_layers.h), written from the
// extensions' texts: KHR_materials_specular's colour, KHR_materials_sheen (Charlie distribution and visibility, the
// base scaled by 1 - max3(colour) E(n.v)) and KHR_materials_clearcoat (a GGX lobe D V weighed by clearcoat F(n.v) at
// ior 1.5, over the rest weighed by one less that). Albedos come from quadratures here, not from rcsplat's tables.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>

#include "brdf_reference.h"

namespace rcsplat::layers_reference {

using brdf_reference::dot;
using brdf_reference::kPi;
using brdf_reference::unit;
using brdf_reference::Vec;

struct Layered {
  std::array<double, 3> base;
  double metallic = 0.0, roughness = 1.0, specular = 1.0;
  std::array<double, 3> specular_color{1.0, 1.0, 1.0};
  double clearcoat = 0.0, clearcoat_roughness = 0.0;
  std::array<double, 3> sheen{0.0, 0.0, 0.0};
  double sheen_roughness = 0.0;
  Vec coat_normal{0.0, 0.0, 1.0};  // unit, in the frame of the shading normal (+z)
};

inline double max3(const std::array<double, 3>& c) { return std::max({c[0], c[1], c[2]}); }

// GGX with height-correlated Smith masking, D G2 / (4 n.l n.v), about the unit normal n.
inline double ggx_lobe(double alpha, Vec wo, Vec wi, Vec n = {0.0, 0.0, 1.0}) {
  const double cos_o = dot(wo, n), cos_i = dot(wi, n);
  if (cos_o <= 0.0 || cos_i <= 0.0) return 0.0;
  const double cos_h = dot(unit(wo + wi), n);
  const double g2 = 1.0 / (1.0 + brdf_reference::lambda_ggx(cos_o, alpha) + brdf_reference::lambda_ggx(cos_i, alpha));
  return brdf_reference::d_ggx(cos_h, alpha) * g2 / (4.0 * cos_o * cos_i);
}

// The GGX lobe's albedo toward a view at cos_o for a Fresnel of 1 (a0) and of (1 - v.h)^5 (a1), over half vectors
// drawn from D(h) cos(theta_h) by the midpoint rule.
inline std::array<double, 2> ggx_albedo_terms(double cos_o, double alpha, int n = 256) {
  const Vec wo{std::sqrt(std::max(1.0 - cos_o * cos_o, 0.0)), 0.0, cos_o};
  double a0 = 0.0, a1 = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n, phi = 2.0 * kPi * (j + 0.5) / n;
      const double ch = 1.0 / std::sqrt(1.0 + alpha * alpha * u / (1.0 - u)), sh = std::sqrt(1.0 - ch * ch);
      const Vec h{sh * std::cos(phi), sh * std::sin(phi), ch};
      const double wo_h = dot(wo, h);
      const Vec wi = (2.0 * wo_h) * h + (-1.0) * wo;
      if (wo_h <= 0.0 || wi.z <= 0.0) continue;
      const double g2 = 1.0 / (1.0 + brdf_reference::lambda_ggx(cos_o, alpha) + brdf_reference::lambda_ggx(wi.z, alpha));
      const double w = g2 * wo_h / (cos_o * ch);
      a0 += w;
      a1 += brdf_reference::schlick(wo_h) * w;
    }
  const double count = double(n) * n;
  return {a0 / count, a1 / count};
}

inline double sheen_alpha(double roughness) { return std::max(roughness * roughness, 1e-3); }

// The Charlie sheen distribution for cos(theta_h), and its visibility with the fitted Lambda (the extension's text).
inline double charlie_d(double cos_h, double alpha) {
  const double sin2 = std::max(1.0 - cos_h * cos_h, 0.0);
  return (2.0 + 1.0 / alpha) * std::pow(sin2, 0.5 / alpha) / (2.0 * kPi);
}
inline double charlie_l(double x, double alpha) {
  const double t = (1.0 - alpha) * (1.0 - alpha);
  auto mix = [t](double a, double b) { return a + (b - a) * t; };
  return mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
         mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
}
inline double charlie_lambda(double cos_t, double alpha) {
  return cos_t < 0.5 ? std::exp(charlie_l(cos_t, alpha)) : std::exp(2.0 * charlie_l(0.5, alpha) - charlie_l(1.0 - cos_t, alpha));
}
inline double sheen_lobe(double alpha, Vec wo, Vec wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  const Vec h = unit(wo + wi);
  return charlie_d(h.z, alpha) / ((1.0 + charlie_lambda(wo.z, alpha) + charlie_lambda(wi.z, alpha)) * 4.0 * wo.z * wi.z);
}

// The sheen lobe's directional albedo toward cos_o, by the midpoint rule in (theta_i, phi_i) (a different rule from
// host/tables/make_sheen_albedo.cpp's cosine-weighted grid).
inline double sheen_albedo(double cos_o, double roughness, int n = 400) {
  const double alpha = sheen_alpha(roughness);
  const Vec wo{std::sqrt(std::max(1.0 - cos_o * cos_o, 0.0)), 0.0, cos_o};
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double theta = 0.5 * kPi * (i + 0.5) / n, phi = kPi * (j + 0.5) / n;
      const Vec wi{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      sum += sheen_lobe(alpha, wo, wi) * wi.z * std::sin(theta);
    }
  return sum * (0.5 * kPi / n) * (kPi / n);
}

// f(wo, wi) of the layered BRDF about the shading normal (+z), the coat's lobe and Fresnel about its own normal. Its
// diffuse part's weight reads the
// base lobe's albedo terms and the sheen's albedo from the quadratures above, given here (they depend on the view
// only): terms = ggx_albedo_terms(wo.z, base alpha), sheen_e = min(sheen_albedo(wo.z, sheen roughness), 1).
inline std::array<double, 3> layered_brdf(const Layered& m, Vec wo, Vec wi, std::array<double, 2> terms, double sheen_e) {
  std::array<double, 3> f{0.0, 0.0, 0.0};
  if (wo.z <= 0.0 || wi.z <= 0.0) return f;
  const double alpha = std::max(m.roughness * m.roughness, 1e-3);
  const double lobe = ggx_lobe(alpha, wo, wi), fw = brdf_reference::schlick(dot(wo, unit(wo + wi)));
  std::array<double, 3> f0;
  double taken = 0.0;  // max3 of the dielectric lobe's albedo
  for (int c = 0; c < 3; ++c) {
    f0[size_t(c)] = std::min(0.04 * m.specular_color[size_t(c)], 1.0);
    taken = std::max(taken, m.specular * (f0[size_t(c)] * terms[0] + (1.0 - f0[size_t(c)]) * terms[1]));
  }
  const double coat = m.clearcoat * (0.04 + 0.96 * brdf_reference::schlick(std::max(dot(wo, m.coat_normal), 0.0)));
  const double sheen_scale = 1.0 - max3(m.sheen) * sheen_e;
  const double coat_alpha = std::max(m.clearcoat_roughness * m.clearcoat_roughness, 1e-3);
  const double sheen = sheen_lobe(sheen_alpha(m.sheen_roughness), wo, wi), coat_lobe = ggx_lobe(coat_alpha, wo, wi, m.coat_normal);
  for (size_t c = 0; c < 3; ++c) {
    const double b = m.base[c];
    const double dielectric = (1.0 - taken) * b / kPi + m.specular * (f0[c] + (1.0 - f0[c]) * fw) * lobe;
    const double metal = (b + (1.0 - b) * fw) * lobe;
    const double base = (1.0 - m.metallic) * dielectric + m.metallic * metal;
    f[c] = (1.0 - coat) * (m.sheen[c] * sheen + sheen_scale * base) + coat * coat_lobe;
  }
  return f;
}

}  // namespace rcsplat::layers_reference
