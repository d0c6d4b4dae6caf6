// An independent double-precision model of rcsplat's BRDF (kernels/brdf.h), written from glTF 2.0's appendix B, and
// its directional albedo by quadrature: the reference the BRDF, furnace and composition tests compare against.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <type_traits>

namespace rcsplat::brdf_reference {

constexpr double kPi = std::numbers::pi;

struct Vec {
  double x, y, z;
};
inline Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec operator*(double s, Vec a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec unit(Vec a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

struct Material {
  std::array<double, 3> base;
  double metallic, roughness, specular;
};

inline double alpha_of(const Material& m) { return std::max(m.roughness * m.roughness, 1e-3); }

// GGX's Smith Lambda, distribution D (for cos(theta_h)) and Schlick's Fresnel weight (1 - v.h)^5.
inline double lambda_ggx(double cos_t, double a) {
  double tan2 = (1.0 - cos_t * cos_t) / (cos_t * cos_t);
  return 0.5 * (std::sqrt(1.0 + a * a * tan2) - 1.0);
}
inline double d_ggx(double cos_h, double a) {
  double c2 = cos_h * cos_h, t2 = (1.0 - c2) / c2;
  double k = a * a + t2;
  return a * a / (kPi * c2 * c2 * k * k);
}
inline double schlick(double v_dot_h) { return std::pow(std::clamp(1.0 - v_dot_h, 0.0, 1.0), 5.0); }

// The dielectric lobe's directional albedo toward a view at cos_o, for specular 1: the integral of
// F_d(v.h) D G2 / (4 n.v) over half vectors drawn from D(h) cos(theta_h) (the reflection's density D cos / (4 v.h)), by
// the midpoint rule on an n x n grid. The last value is kept: the quadratures below ask for one view many times.
inline double dielectric_lobe_albedo(double cos_o, double a, int n = 128) {
  thread_local double kept_cos = -1.0, kept_a = -1.0, kept = 0.0;
  thread_local int kept_n = 0;
  if (cos_o == kept_cos && a == kept_a && n == kept_n) return kept;
  Vec wo{std::sqrt(std::max(1.0 - cos_o * cos_o, 0.0)), 0.0, cos_o};
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double u = (i + 0.5) / n, phi = 2.0 * kPi * (j + 0.5) / n;
      double ch = 1.0 / std::sqrt(1.0 + a * a * u / (1.0 - u)), sh = std::sqrt(1.0 - ch * ch);
      Vec h{sh * std::cos(phi), sh * std::sin(phi), ch};
      double wo_h = dot(wo, h);
      Vec wi = (2.0 * wo_h) * h + (-1.0) * wo;
      if (wo_h <= 0.0 || wi.z <= 0.0) continue;
      double g2 = 1.0 / (1.0 + lambda_ggx(cos_o, a) + lambda_ggx(wi.z, a));
      // f cos / pdf = F D G2 / (4 n.v n.l) n.l 4 v.h / (D cos_h) = F G2 v.h / (n.v cos_h)
      sum += (0.04 + 0.96 * schlick(wo_h)) * g2 * wo_h / (cos_o * ch);
    }
  kept_cos = cos_o, kept_a = a, kept_n = n;
  return kept = sum / (double(n) * n);
}

// How a dielectric's diffuse base is weighted: rcsplat's 1 - E_d(n.v) (kernels/brdf.h says why), appendix B's own
// 1 - F_d(v.h) per microfacet, or 1 - F_d(n.v), rcsplat's weight before issue 41.
enum class DiffuseWeight { view_albedo, per_microfacet, view_fresnel };

// glTF 2.0 appendix B in double, written from the specification's formulas: GGX D, height-correlated Smith V (as
// G2 / (4 n.l n.v) from the Smith Lambda functions), Schlick Fresnel, with the diffuse weighted as `weight` says.
// Split into its diffuse and specular parts so the quadrature can integrate each where it is smooth.
inline std::array<double, 3> reference_brdf(const Material& m, Vec wo, Vec wi, bool diffuse_part, bool specular_part,
                                            DiffuseWeight weight = DiffuseWeight::view_albedo) {
  std::array<double, 3> f{0.0, 0.0, 0.0};
  if (wo.z <= 0.0 || wi.z <= 0.0) return f;
  Vec h = unit(wo + wi);
  double a = alpha_of(m);
  double g2 = 1.0 / (1.0 + lambda_ggx(wo.z, a) + lambda_ggx(wi.z, a));
  double spec = d_ggx(h.z, a) * g2 / (4.0 * wo.z * wi.z);
  double fw = schlick(dot(wo, h));
  double fd = m.specular * (0.04 + 0.96 * fw);
  double taken = 0.0;  // what the specular layer takes from the diffuse base
  if (diffuse_part && m.specular > 0.0) {
    if (weight == DiffuseWeight::per_microfacet) taken = fd;
    else if (weight == DiffuseWeight::view_fresnel) taken = m.specular * (0.04 + 0.96 * schlick(wo.z));
    else taken = m.specular * dielectric_lobe_albedo(wo.z, a);
  }
  for (int c = 0; c < 3; ++c) {
    double diffuse = (1.0 - m.metallic) * (1.0 - taken) * m.base[size_t(c)] / kPi;
    double specular = (1.0 - m.metallic) * fd * spec + m.metallic * (m.base[size_t(c)] + (1.0 - m.base[size_t(c)]) * fw) * spec;
    f[size_t(c)] = (diffuse_part ? diffuse : 0.0) + (specular_part ? specular : 0.0);
  }
  return f;
}

// Incident radiance given as a function of the direction, or of cos(theta) alone.
template <typename Incident>
double incident_radiance(const Incident& incident, Vec wi) {
  if constexpr (std::is_invocable_v<Incident, Vec>) return incident(wi);
  else return incident(wi.z);
}

// The radiance reflected toward wo from incident radiance `incident` (of the direction, or of cos theta_i): the
// diffuse part over cosine-weighted directions, the specular part over half vectors drawn from D(h) cos(theta_h) (so
// the integrand stays smooth however narrow the lobe), both by the midpoint rule on an n x n grid.

template <typename Incident>
std::array<double, 3> reference_reflected(const Material& m, Vec wo, Incident incident, DiffuseWeight weight, int n) {
  std::array<double, 3> sum{0.0, 0.0, 0.0};
  double a = alpha_of(m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double u = (i + 0.5) / n, v = (j + 0.5) / n, phi = 2.0 * kPi * v;
      // Diffuse: wi with pdf cos / pi, so f cos / pdf = f pi.
      double s = std::sqrt(u);
      Vec wi{s * std::cos(phi), s * std::sin(phi), std::sqrt(1.0 - u)};
      std::array<double, 3> fd = reference_brdf(m, wo, wi, true, false, weight);
      double l_diffuse = incident_radiance(incident, wi);
      // Specular: h with pdf D cos(theta_h); wi = reflect(wo, h) has pdf D cos(theta_h) / (4 wo.h).
      double tan2 = a * a * u / (1.0 - u);
      double ch = 1.0 / std::sqrt(1.0 + tan2), sh = std::sqrt(1.0 - ch * ch);
      Vec h{sh * std::cos(phi), sh * std::sin(phi), ch};
      double wo_h = dot(wo, h);
      Vec wr = (2.0 * wo_h) * h + (-1.0) * wo;
      std::array<double, 3> fs{0.0, 0.0, 0.0};
      double pdf = d_ggx(ch, a) * ch / (4.0 * wo_h);
      bool above = wo_h > 0.0 && wr.z > 0.0;
      if (above) fs = reference_brdf(m, wo, wr, false, true);
      double l_specular = above ? incident_radiance(incident, wr) : 0.0;
      for (size_t c = 0; c < 3; ++c)
        sum[c] += fd[c] * kPi * l_diffuse + (above ? fs[c] * wr.z / pdf * l_specular : 0.0);
    }
  for (double& x : sum) x /= double(n) * double(n);
  return sum;
}

// Directional albedo: the radiance reflected from a uniform unit incident radiance.
inline std::array<double, 3> reference_albedo(const Material& m, Vec wo,
                                              DiffuseWeight weight = DiffuseWeight::view_albedo, int n = 600) {
  return reference_reflected(m, wo, [](double) { return 1.0; }, weight, n);
}

}  // namespace rcsplat::brdf_reference
