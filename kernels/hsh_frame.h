// From a radiance record's frame to a pixel's (docs/ALGORITHM.md section 6): the record's coefficients live in the frame
// tangent_frame(n_record); the pixel's BRDF table (kernels/brdf_table.cl) in a frame around the pixel's normal whose
// x axis is the view's azimuth. The change is a tilt carrying the record's normal onto the pixel's (small where the
// record is usable: Ward's weight bounds the angle), taken to first order, lambda + alpha_x D_x lambda +
// alpha_y D_y lambda (host/cache/hsh_rotation.h), then an exact turn by gamma about the pixel's normal.
#ifndef RCSPLAT_HSH_FRAME_H
#define RCSPLAT_HSH_FRAME_H
#include "hsh.h"
#include "sampling.h"
#include "shared_types.h"

typedef struct {
  float tilt_x, tilt_y;  // the tilt's rotation vector in the record's frame (x, y components; it has no z)
  float cos_gamma, sin_gamma;  // then the turn about the pixel's normal onto the view's azimuth
} HshFrameChange;

// The frame change from the record (normal nk, frame t, b = tangent_frame(nk), which the splat builds once per
// record) to the pixel (normal n, unit view direction toward the camera).
inline HshFrameChange hsh_frame_change(float3 nk, float3 t, float3 b, float3 n, float3 view) {
  float a = dot(n, t), bb = dot(n, b), c = dot(n, nk);
  float s = sqrt(a * a + bb * bb), angle = atan2(s, c);
  float per_sin = s > 1e-7f ? angle / s : 1.0f;
  HshFrameChange f;
  f.tilt_x = -bb * per_sin;  // rotation vector nk x n = (-b, a, 0) in the record's frame, scaled to the angle
  f.tilt_y = a * per_sin;
  // The record's tangent carried by the same tilt (Rodrigues), then the view's azimuth around the pixel's normal.
  float3 tilted_t = t;
  if (s > 1e-7f) {
    float3 axis = cross(nk, n) / s;
    tilted_t = t * c + cross(axis, t) * s + axis * (dot(axis, t) * (1.0f - c));
  }
  float3 tilted_b = cross(n, tilted_t);
  float3 view_t = view - n * dot(n, view);
  float x = dot(view_t, tilted_t), y = dot(view_t, tilted_b), len = sqrt(x * x + y * y);
  f.cos_gamma = len > 1e-7f ? x / len : 1.0f;  // a view along the normal has no azimuth: any is right
  f.sin_gamma = len > 1e-7f ? y / len : 0.0f;
  return f;
}

// The record's coefficients at the pixel, still in the record's frame but moved by (dt, db) along its tangent and
// bitangent and tilted: mu_k = lambda_k + dt grad_t + db grad_b + alpha_x (D_x lambda)_k + alpha_y (D_y lambda)_k.
inline float3 hsh_moved_coefficient(__global const float* block, int n2, int k, float dt, float db, HshFrameChange f) {
  return vload3(k, block + HSH_PART_COEFFICIENTS * 3 * n2) + dt * vload3(k, block + HSH_PART_GRADIENT_T * 3 * n2) +
         db * vload3(k, block + HSH_PART_GRADIENT_B * 3 * n2) + f.tilt_x * vload3(k, block + HSH_PART_TILT_X * 3 * n2) +
         f.tilt_y * vload3(k, block + HSH_PART_TILT_Y * 3 * n2);
}

// Reflected radiance: sum over l and m >= 0 of lobe[l, m] times the moved coefficients turned by gamma (the lobe,
// seen from the view's azimuth, has no sin(m phi) part). lobe_a and lobe_b are the table's two Fresnel terms at the
// pixel's view angle, c0 and c1 the pixel's Fresnel colours.
inline float3 hsh_reflected(__global const float* block, int order, float dt, float db, HshFrameChange f,
                            const float* lobe_a, const float* lobe_b, float3 c0, float3 c1) {
  const int n2 = order * order;
  float3 sum = (float3)(0.0f);
  float cos_m = 1.0f, sin_m = 0.0f;  // cos(m gamma), sin(m gamma) by the angle-sum recurrence
  for (int m = 0; m < order; ++m) {
    for (int l = m; l < order; ++l) {
      int k = hsh_index(l, m);
      float3 turned = hsh_moved_coefficient(block, n2, k, dt, db, f) * cos_m;
      if (m > 0) turned += hsh_moved_coefficient(block, n2, hsh_index(l, -m), dt, db, f) * sin_m;
      sum += (c0 * lobe_a[k] + c1 * lobe_b[k]) * turned;
    }
    float c = cos_m * f.cos_gamma - sin_m * f.sin_gamma;
    sin_m = sin_m * f.cos_gamma + cos_m * f.sin_gamma;
    cos_m = c;
  }
  return sum;
}

#endif
