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

// glTF 2.0 appendix B in double, written from the specification's formulas: GGX D, height-correlated Smith V (as
// G2 / (4 n.l n.v) from the Smith Lambda functions), Schlick Fresnel, with the diffuse weighted by the Fresnel of the
// view angle (kernels/brdf.h says why; `per_microfacet_diffuse` gives appendix B's own weight, to show its excess).
// Split into its diffuse and specular parts so the quadrature can integrate each where it is smooth.
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

inline std::array<double, 3> reference_brdf(const Material& m, Vec wo, Vec wi, bool diffuse_part, bool specular_part,
                                     bool per_microfacet_diffuse = false) {
  std::array<double, 3> f{0.0, 0.0, 0.0};
  if (wo.z <= 0.0 || wi.z <= 0.0) return f;
  Vec h = unit(wo + wi);
  double a = alpha_of(m);
  double g2 = 1.0 / (1.0 + lambda_ggx(wo.z, a) + lambda_ggx(wi.z, a));
  double spec = d_ggx(h.z, a) * g2 / (4.0 * wo.z * wi.z);
  double fw = schlick(dot(wo, h));
  double fd = m.specular * (0.04 + 0.96 * fw);
  double fd_diffuse = per_microfacet_diffuse ? fd : m.specular * (0.04 + 0.96 * schlick(wo.z));
  for (int c = 0; c < 3; ++c) {
    double diffuse = (1.0 - m.metallic) * (1.0 - fd_diffuse) * m.base[size_t(c)] / kPi;
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
std::array<double, 3> reference_reflected(const Material& m, Vec wo, Incident incident, bool per_microfacet_diffuse,
                                          int n) {
  std::array<double, 3> sum{0.0, 0.0, 0.0};
  double a = alpha_of(m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double u = (i + 0.5) / n, v = (j + 0.5) / n, phi = 2.0 * kPi * v;
      // Diffuse: wi with pdf cos / pi, so f cos / pdf = f pi.
      double s = std::sqrt(u);
      Vec wi{s * std::cos(phi), s * std::sin(phi), std::sqrt(1.0 - u)};
      std::array<double, 3> fd = reference_brdf(m, wo, wi, true, false, per_microfacet_diffuse);
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
inline std::array<double, 3> reference_albedo(const Material& m, Vec wo, bool per_microfacet_diffuse = false,
                                              int n = 600) {
  return reference_reflected(m, wo, [](double) { return 1.0; }, per_microfacet_diffuse, n);
}

}  // namespace rcsplat::brdf_reference
