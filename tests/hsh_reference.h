// Hemispherical harmonics in double precision, from the definition (docs/ALGORITHM.md section 6), written apart from
// kernels/hsh.h: the reference of the HSH tests.
#pragma once
#include <cmath>
#include <cstdlib>
#include <numbers>

namespace rcsplat {

// H_l^m at (cos_theta, phi) about +z.
inline double reference_hsh(int l, int m, double cos_theta, double phi) {
  int am = std::abs(m);
  double x = 2.0 * cos_theta - 1.0;
  double k = std::sqrt((2.0 * l + 1.0) / (2.0 * std::numbers::pi) *
                       std::exp(std::lgamma(l - am + 1.0) - std::lgamma(l + am + 1.0)));
  double p = std::assoc_legendre(unsigned(l), unsigned(am), x);  // no Condon-Shortley phase, as hsh.h
  if (m == 0) return k * p;
  return std::sqrt(2.0) * k * p * (m > 0 ? std::cos(m * phi) : std::sin(am * phi));
}

}  // namespace rcsplat
