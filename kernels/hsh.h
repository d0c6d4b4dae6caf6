// Hemispherical harmonics (Gautron et al. 2004; docs/ALGORITHM.md section 6): an orthonormal basis over the hemisphere
// around +z, compiled by the kernels and by the host. With the shifted argument x = 2 cos(theta) - 1 and the
// associated Legendre functions P_l^m (without the Condon-Shortley phase),
//   H_l^m = sqrt(2) K_l^m cos(m phi) P_l^m(x)        for m > 0,
//   H_l^0 = K_l^0 P_l^0(x),
//   H_l^m = sqrt(2) K_l^|m| sin(|m| phi) P_l^|m|(x)  for m < 0,
//   K_l^m = sqrt((2l + 1) (l - m)! / (2 pi (l + m)!)).
// Order n uses l = 0 .. n - 1: n^2 functions, stored at index l (l + 1) + m.
// The recurrences run on K_l^m P_l^m directly (normalised), so no factorial is formed: stable at theta = pi/2
// (x = -1), at the pole (x = 1) and for the highest order offered.
#ifndef RCSPLAT_HSH_H
#define RCSPLAT_HSH_H
#include "host_device.h"

#define HSH_MAX_ORDER 10
#define HSH_MAX_COEFFICIENTS (HSH_MAX_ORDER * HSH_MAX_ORDER)

inline int hsh_index(int l, int m) { return l * (l + 1) + m; }

// N_l^m = K_l^m P_l^m(2 cos(theta) - 1) for 0 <= m <= l < order, into out[hsh_index(l, m)] (the m < 0 slots are
// left alone).
inline void hsh_legendre(float cos_theta, int order, float* out) {
  float c = rc_fmin(rc_fmax(cos_theta, 0.0f), 1.0f);
  float x = 2.0f * c - 1.0f;
  // sqrt(1 - x^2) = 2 sqrt(c (1 - c)), from c itself: near the horizon x = 2c - 1 has lost c's low bits.
  float s = 2.0f * rc_sqrt(c * (1.0f - c));
  // N_l^m is sqrt(2) times the usual spherical-harmonic normalisation, so it follows the same recurrences:
  // N_0^0 = 1 / sqrt(2 pi), N_m^m = sqrt((2m + 1) / (2m)) s N_{m-1}^{m-1}, and up in l for each m
  // N_l = sqrt((4 l^2 - 1) / (l^2 - m^2)) (x N_{l-1} - sqrt(((l - 1)^2 - m^2) / (4 (l - 1)^2 - 1)) N_{l-2}),
  // whose second term vanishes at l = m + 1.
  float pmm = 0.3989422804014327f;
  for (int m = 0; m < order; ++m) {
    if (m > 0) pmm *= rc_sqrt((2.0f * (float)m + 1.0f) / (2.0f * (float)m)) * s;
    float p_prev = 0.0f, p = pmm;
    for (int l = m; l < order; ++l) {
      if (l > m) {
        float lf = (float)l, mf = (float)m;
        float a = rc_sqrt((4.0f * lf * lf - 1.0f) / (lf * lf - mf * mf));
        float b = rc_sqrt(((lf - 1.0f) * (lf - 1.0f) - mf * mf) / (4.0f * (lf - 1.0f) * (lf - 1.0f) - 1.0f));
        float next = a * (x * p - b * p_prev);
        p_prev = p;
        p = next;
      }
      out[hsh_index(l, m)] = p;
    }
  }
}

// All order^2 basis functions at the direction (cos_theta, phi), cos_theta in [0, 1], into out[0 .. order^2 - 1].
inline void hsh_basis(float cos_theta, float phi, int order, float* out) {
  hsh_legendre(cos_theta, order, out);
  float cos_phi = rc_cos(phi), sin_phi = rc_sin(phi);
  float cos_m = cos_phi, sin_m = sin_phi;  // cos(m phi), sin(m phi) by the angle-sum recurrence
  for (int m = 1; m < order; ++m) {
    for (int l = m; l < order; ++l) {
      float n = out[hsh_index(l, m)];
      out[hsh_index(l, m)] = 1.41421356f * n * cos_m;
      out[hsh_index(l, -m)] = 1.41421356f * n * sin_m;
    }
    float c = cos_m * cos_phi - sin_m * sin_phi;
    sin_m = sin_m * cos_phi + cos_m * sin_phi;
    cos_m = c;
  }
}

// Projection of incident radiance from a record's M x N strata (equal in sin^2(theta) and phi, docs/ALGORITHM.md
// section 5), with the radiance taken constant in each stratum and the basis integrated over it exactly, so that a
// constant projects exactly and no sample carries the 1 / cos(theta) weight of the cosine-weighted pdf (unbounded
// variance at the horizon). Separable: lambda_l^m = sum_rows R_row^{l|m|} sum_columns L Phi_column^m, with
// Phi the integral of sqrt(2) cos(m phi) (m > 0), 1 (m = 0) or sqrt(2) sin(|m| phi) (m < 0) over the column
// (tabulated by the host: passes/hsh_record_pass.h hsh_column_table).

// R_row^{lm} = integral over the row of N_l^m sin(theta) d theta = integral of N_l^m d(cos theta) over the row,
// by 8-point Gauss-Legendre, into out[hsh_index(l, m)] for m >= 0.
inline void hsh_row_integrals(int row, int rows, int order, float* out) {
  const float node[4] = {0.1834346424956498f, 0.5255324099163290f, 0.7966664774136267f, 0.9602898564975363f};
  const float weight[4] = {0.3626837833783620f, 0.3137066458778873f, 0.2223810344533745f, 0.1012285362903763f};
  float cos_lo = rc_sqrt(1.0f - (float)row / (float)rows);
  float cos_hi = rc_sqrt(rc_fmax(1.0f - (float)(row + 1) / (float)rows, 0.0f));
  float mid = 0.5f * (cos_lo + cos_hi), half_span = 0.5f * (cos_lo - cos_hi);  // in cos(theta): d omega = d cos dphi
  for (int l = 0; l < order; ++l)
    for (int m = 0; m <= l; ++m) out[hsh_index(l, m)] = 0.0f;
  float n[HSH_MAX_COEFFICIENTS];
  for (int g = 0; g < 8; ++g) {
    float t = g < 4 ? node[g] : -node[g - 4], w = weight[g < 4 ? g : g - 4] * half_span;
    hsh_legendre(mid + half_span * t, order, n);
    for (int l = 0; l < order; ++l)
      for (int m = 0; m <= l; ++m) out[hsh_index(l, m)] += w * n[hsh_index(l, m)];
  }
}

// The radiance the coefficients describe in the direction (cos_theta, phi).
inline float hsh_evaluate(const float* coefficients, int order, float cos_theta, float phi) {
  float basis[HSH_MAX_COEFFICIENTS];
  hsh_basis(cos_theta, phi, order, basis);
  float sum = 0.0f;
  for (int k = 0; k < order * order; ++k) sum += coefficients[k] * basis[k];
  return sum;
}

#endif
