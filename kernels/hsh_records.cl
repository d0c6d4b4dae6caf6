// Radiance records (Křivánek et al. 2005; docs/ALGORITHM.md sections 5 and 6): the incident radiance a record's M x N
// strata saw (kernels/records.cl with STORE_STRATA) projected onto hemispherical harmonics in the record's frame
// (tangent_frame of its normal), with the translational gradient of every coefficient, then the tilt derivatives
// D_x lambda and D_y lambda that the splat needs to turn the coefficients into each pixel's frame.
//
// Projection (kernels/hsh.h): radiance constant in each stratum, basis integrated exactly over it, separable in rows
// and columns. Gradients: Ward and Heckbert's translational gradient generalised from irradiance to each coefficient
// (Křivánek et al. 2005): moving the point by d in the tangent plane moves the walls between strata; the wall
// between rows j - 1 and j (at theta_j) sweeps d . u(phi) cos(theta_j) / r of angle per unit length, the wall between
// columns k - 1 and k (at phi_k) d . v(phi_k) / (r sin theta), where r is the nearer of the two hits. Each moving wall
// trades the radiance on one side for the other's, weighted by H_k on the wall:
//   dlambda_k += (L_j - L_{j-1}) / r * sin(theta_j) cos(theta_j) * integral over the column of u(phi) H_k(theta_j, phi)
//   dlambda_k += (L_k - L_{k-1}) / r * v(phi_k) * integral over the row of H_k(theta, phi_k) d theta.
// With H = cos(theta) these are the irradiance gradient of kernels/records.cl.
#include "hsh.h"
#include "shared_types.h"

// Per column k and azimuthal index m (-(n - 1) .. n - 1, slot m + n - 1), five numbers that depend on neither the
// record nor the row, tabulated by the host (passes/hsh_record_pass.cpp) for the batch's N:
// COLUMN_PHI: the integral over the column of the azimuthal factor of H^m (sqrt(2) cos(m phi), 1, sqrt(2) sin(|m| phi));
// COLUMN_WALL_T, _B: the integral over the column of u(phi) = (cos phi, sin phi) times that factor (theta walls);
// COLUMN_SIDE_T, _B: v(phi_k) = (-sin phi_k, cos phi_k) times the factor at phi_k (the wall at the column's start).
#define COLUMN_PHI 0
#define COLUMN_WALL_T 1
#define COLUMN_WALL_B 2
#define COLUMN_SIDE_T 3
#define COLUMN_SIDE_B 4
#define COLUMN_TERMS 5

// out[hsh_index(l, m)] (m >= 0) = integral over the row of N_l^m(cos theta) d theta, by 8-point Gauss-Legendre in
// theta (the row's walls are equal in sin^2 theta).
inline void row_theta_integrals(int row, int rows, int order, float* out) {
  const float node[4] = {0.1834346424956498f, 0.5255324099163290f, 0.7966664774136267f, 0.9602898564975363f};
  const float weight[4] = {0.3626837833783620f, 0.3137066458778873f, 0.2223810344533745f, 0.1012285362903763f};
  float theta_lo = asin(sqrt((float)row / (float)rows)), theta_hi = asin(sqrt((float)(row + 1) / (float)rows));
  float mid = 0.5f * (theta_lo + theta_hi), half_span = 0.5f * (theta_hi - theta_lo);
  for (int l = 0; l < order; ++l)
    for (int m = 0; m <= l; ++m) out[hsh_index(l, m)] = 0.0f;
  float n[HSH_MAX_COEFFICIENTS];
  for (int g = 0; g < 8; ++g) {
    float t = g < 4 ? node[g] : -node[g - 4], w = weight[g < 4 ? g : g - 4] * half_span;
    hsh_legendre(cos(mid + half_span * t), order, n);
    for (int l = 0; l < order; ++l)
      for (int m = 0; m <= l; ++m) out[hsh_index(l, m)] += w * n[hsh_index(l, m)];
  }
}

// part[k] += factor[hsh_index(l, |m|)] * by_m[order - 1 + m] for every (l, m): the separable sums' last step.
inline void add_separable(__global float* part, int order, const float* factor, const float3* by_m) {
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) {
      int k = hsh_index(l, m);
      vstore3(vload3(k, part) + factor[hsh_index(l, m < 0 ? -m : m)] * by_m[order - 1 + m], k, part);
    }
}

// Bounds a record's translational gradients as kernels/records.cl bounds the irradiance's (|grad E| <= E / R): per
// channel, the gradients' L2 norm over the hemisphere (the basis is orthonormal) at most the radiance's own over the
// radius, so that moving a record's light across its reach never changes it by more than the light itself. Unbounded,
// a record beside a wall (hit distances far below its radius) extrapolated its brightest strata into hot pixels.
inline void bound_hsh_gradients(__global const float* lambda, __global float* grad_t, __global float* grad_b, int n2,
                                float radius) {
  float3 light = (float3)(0.0f), change = (float3)(0.0f);
  for (int k = 0; k < n2; ++k) {
    float3 l = vload3(k, lambda), gt = vload3(k, grad_t), gb = vload3(k, grad_b);
    light += l * l;
    change += gt * gt + gb * gb;
  }
  float3 limit = sqrt(light) / radius, norm = sqrt(change);
  float3 scale = select((float3)(1.0f), limit / norm, isgreater(norm, limit));
  scale = select(scale, (float3)(0.0f), isnan(scale) | isless(scale, 0.0f));
  for (int k = 0; k < n2; ++k) {
    vstore3(vload3(k, grad_t) * scale, k, grad_t);
    vstore3(vload3(k, grad_b) * scale, k, grad_b);
  }
}

// One work item per record of the batch.
__kernel void project_radiance_records(__global const float4* strata, __global const float* column_table,
                                       __global const CacheRecord* records, HshRecordParams params,
                                       __global float* coefficients, __global uint* max_radiance_bits) {
  uint i = get_global_id(0);
  if (i >= params.record_count) return;
  const int order = (int)params.order, n2 = order * order, width = 2 * order - 1;
  const int M = (int)params.theta_strata, N = (int)params.phi_strata;
  __global float* block = coefficients + (size_t)(params.first_record + i) * (size_t)(HSH_RECORD_PARTS * 3 * n2);
  __global float* lambda = block + HSH_PART_COEFFICIENTS * 3 * n2;
  __global float* grad_t = block + HSH_PART_GRADIENT_T * 3 * n2;
  __global float* grad_b = block + HSH_PART_GRADIENT_B * 3 * n2;
  for (int k = 0; k < 3 * 3 * n2; ++k) block[k] = 0.0f;
  __global const float4* s = strata + (size_t)i * (size_t)(M * N);
  float largest = 0.0f;

  float row_integrals[HSH_MAX_COEFFICIENTS], wall_legendre[HSH_MAX_COEFFICIENTS], theta_integrals[HSH_MAX_COEFFICIENTS];
  float3 row_sums[2 * HSH_MAX_ORDER - 1], wall_t[2 * HSH_MAX_ORDER - 1], wall_b[2 * HSH_MAX_ORDER - 1];
  float3 side_t[2 * HSH_MAX_ORDER - 1], side_b[2 * HSH_MAX_ORDER - 1];
  for (int j = 0; j < M; ++j) {
    for (int m = 0; m < width; ++m) {
      row_sums[m] = wall_t[m] = wall_b[m] = side_t[m] = side_b[m] = (float3)(0.0f);
    }
    for (int k = 0; k < N; ++k) {
      float4 here = s[j * N + k];
      float3 l = here.xyz;
      largest = fmax(largest, fmax(fmax(l.x, l.y), l.z));
      // The wall toward the previous row (j > 0) and toward the previous column (wrapping at phi = 0).
      float4 below = j > 0 ? s[(j - 1) * N + k] : here;
      float4 before = s[j * N + (k + N - 1) % N];
      float3 theta_step = (l - below.xyz) / fmin(here.w, below.w);
      float3 phi_step = (l - before.xyz) / fmin(here.w, before.w);
      __global const float* column = column_table + (size_t)k * (size_t)(width * COLUMN_TERMS);
      for (int m = 0; m < width; ++m) {
        __global const float* c = column + m * COLUMN_TERMS;
        row_sums[m] += l * c[COLUMN_PHI];
        wall_t[m] += c[COLUMN_WALL_T] * theta_step;
        wall_b[m] += c[COLUMN_WALL_B] * theta_step;
        side_t[m] += c[COLUMN_SIDE_T] * phi_step;
        side_b[m] += c[COLUMN_SIDE_B] * phi_step;
      }
    }
    hsh_row_integrals(j, M, order, row_integrals);
    add_separable(lambda, order, row_integrals, row_sums);
    if (j > 0) {
      float sin2 = (float)j / (float)M, sin_t = sqrt(sin2), cos_t = sqrt(1.0f - sin2);
      hsh_legendre(cos_t, order, wall_legendre);
      for (int k = 0; k < n2; ++k) wall_legendre[k] *= sin_t * cos_t;
      add_separable(grad_t, order, wall_legendre, wall_t);
      add_separable(grad_b, order, wall_legendre, wall_b);
    }
    row_theta_integrals(j, M, order, theta_integrals);
    add_separable(grad_t, order, theta_integrals, side_t);
    add_separable(grad_b, order, theta_integrals, side_b);
  }
  for (int k = 0; k < 3 * 3 * n2; ++k) block[k] = isfinite(block[k]) ? block[k] : 0.0f;
  bound_hsh_gradients(lambda, grad_t, grad_b, n2, records[params.first_record + i].radius);
  if (isfinite(largest)) atomic_max(max_radiance_bits, as_uint(largest));
}

// Kept records fitted to a new view (kernels/placement.cl fit_kept_records), records 0 .. record_count - 1: a reach grown
// past the kept one gets its gradients bounded for it, as a record placed here with that radius would have them.
__kernel void bound_fitted_radiance_gradients(__global const CacheRecord* records, __global const float* kept_radii,
                                              HshRecordParams params, __global float* coefficients) {
  uint i = get_global_id(0);
  if (i >= params.record_count) return;
  float radius = records[i].radius;
  if (!(radius > kept_radii[i])) return;
  const int n2 = (int)(params.order * params.order);
  __global float* block = coefficients + (size_t)i * (size_t)(HSH_RECORD_PARTS * 3 * n2);
  bound_hsh_gradients(block + HSH_PART_COEFFICIENTS * 3 * n2, block + HSH_PART_GRADIENT_T * 3 * n2,
                      block + HSH_PART_GRADIENT_B * 3 * n2, n2, radius);
}

// D_x lambda and D_y lambda (host/cache/hsh_rotation.h), one work item per (record, coefficient).
__kernel void tilt_radiance_records(__global const float* tilt_x, __global const float* tilt_y, HshRecordParams params,
                                    __global float* coefficients) {
  const int n2 = (int)(params.order * params.order);
  uint item = get_global_id(0);
  if (item >= params.record_count * (uint)n2) return;
  uint i = item / (uint)n2;
  int k = (int)(item % (uint)n2);
  __global float* block = coefficients + (size_t)(params.first_record + i) * (size_t)(HSH_RECORD_PARTS * 3 * n2);
  __global const float* lambda = block + HSH_PART_COEFFICIENTS * 3 * n2;
  float3 dx = (float3)(0.0f), dy = (float3)(0.0f);
  for (int q = 0; q < n2; ++q) {
    float3 c = vload3(q, lambda);
    dx += tilt_x[k * n2 + q] * c;
    dy += tilt_y[k * n2 + q] * c;
  }
  vstore3(dx, k, block + HSH_PART_TILT_X * 3 * n2);
  vstore3(dy, k, block + HSH_PART_TILT_Y * 3 * n2);
}
