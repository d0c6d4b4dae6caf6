// Hemispherical harmonics (Gautron et al. 2004; ALGORITHM.md section 6): an orthonormal basis over the hemisphere
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

// All order^2 basis functions at the direction (cos_theta, phi), cos_theta in [0, 1], into out[0 .. order^2 - 1].
inline void hsh_basis(float cos_theta, float phi, int order, float* out) {
  float c = rc_fmin(rc_fmax(cos_theta, 0.0f), 1.0f);
  float x = 2.0f * c - 1.0f;
  // sqrt(1 - x^2) = 2 sqrt(c (1 - c)), from c itself: near the horizon x = 2c - 1 has lost c's low bits.
  float s = 2.0f * rc_sqrt(c * (1.0f - c));
  // N_l^m = K_l^m P_l^m is sqrt(2) times the usual spherical-harmonic normalisation, so it follows the same
  // recurrences: N_0^0 = 1 / sqrt(2 pi), N_m^m = sqrt((2m + 1) / (2m)) s N_{m-1}^{m-1}.
  float pmm = 0.3989422804014327f;
  float cos_m = 1.0f, sin_m = 0.0f;  // cos(m phi), sin(m phi) by the angle-sum recurrence
  float cos_phi = rc_cos(phi), sin_phi = rc_sin(phi);
  for (int m = 0; m < order; ++m) {
    if (m > 0) {
      pmm *= rc_sqrt((2.0f * (float)m + 1.0f) / (2.0f * (float)m)) * s;
      float c = cos_m * cos_phi - sin_m * sin_phi;
      sin_m = sin_m * cos_phi + cos_m * sin_phi;
      cos_m = c;
    }
    // Up in l for this m: N_l = sqrt((4 l^2 - 1) / (l^2 - m^2)) (x N_{l-1} - sqrt(((l - 1)^2 - m^2) /
    // (4 (l - 1)^2 - 1)) N_{l-2}), whose second term vanishes at l = m + 1.
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
      if (m == 0) {
        out[hsh_index(l, 0)] = p;
      } else {
        out[hsh_index(l, m)] = 1.41421356f * p * cos_m;
        out[hsh_index(l, -m)] = 1.41421356f * p * sin_m;
      }
    }
  }
}

#endif
