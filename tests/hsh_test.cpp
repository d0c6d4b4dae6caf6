// Hemispherical harmonics (kernels/hsh.h), compiled for the device and the host: against an independent
// double-precision reference built on std::assoc_legendre, orthonormal over the hemisphere up to the highest order
// offered (by Gauss-Legendre quadrature, exact for these polynomials), and stable at theta = pi/2 and at the pole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "cache/hsh_rotation.h"
#include "kernels/counter_random.h"
#include "kernels/hsh.h"
#include "passes/hsh_record_pass.h"
#include "hsh_reference.h"
#include "test_support.h"

namespace rcsplat {
namespace {

// Directions of a quadrature over the hemisphere exact for products of two basis functions up to HSH_MAX_ORDER:
// Gauss-Legendre in x = 2 cos(theta) - 1 (d omega = dx dphi / 2) and equal steps in phi.
struct HemisphereQuadrature {
  std::vector<float> cos_theta, phi;
  std::vector<double> weight;
  HemisphereQuadrature() {
    std::vector<double> x, w;
    gauss_legendre(HSH_MAX_ORDER + 2, -1.0, 1.0, x, w);
    const int phis = 2 * HSH_MAX_ORDER + 2;
    for (size_t i = 0; i < x.size(); ++i)
      for (int j = 0; j < phis; ++j) {
        cos_theta.push_back(float((x[i] + 1.0) / 2.0));
        phi.push_back(float(2.0 * std::numbers::pi * (j + 0.5) / phis));
        weight.push_back(w[i] / 2.0 * 2.0 * std::numbers::pi / phis);
      }
  }
};

const char* kEvaluateHsh = R"(
#include "hsh.h"
__kernel void evaluate_hsh(__global const float* cos_theta, __global const float* phi, uint count,
                           __global float* out) {
  uint i = get_global_id(0);
  if (i >= count) return;
  float basis[HSH_MAX_COEFFICIENTS];
  hsh_basis(cos_theta[i], phi[i], HSH_MAX_ORDER, basis);
  for (int k = 0; k < HSH_MAX_COEFFICIENTS; ++k) out[(size_t)i * HSH_MAX_COEFFICIENTS + k] = basis[k];
}
)";

std::vector<float> device_basis(const std::vector<float>& cos_theta, const std::vector<float>& phi) {
  GpuContext& gpu = test::gpu();
  cl::Buffer c = gpu.upload(cos_theta), p = gpu.upload(phi);
  cl::Buffer out(gpu.context(), CL_MEM_WRITE_ONLY, cos_theta.size() * HSH_MAX_COEFFICIENTS * sizeof(float));
  NamedKernel kernel(gpu, gpu.program_from_text("hsh_test.cl", kEvaluateHsh), "evaluate_hsh");
  kernel.set_buffer<cl_float>("cos_theta", c).set_buffer<cl_float>("phi", p).set("count", cl_uint(cos_theta.size()));
  kernel.set_buffer<cl_float>("out", out);
  kernel.launch(cos_theta.size(), 64);
  gpu.queue().finish();
  return gpu.download<float>(out, cos_theta.size() * HSH_MAX_COEFFICIENTS);
}

TEST(Hsh, DeviceAndHostMatchTheDoublePrecisionDefinition) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::vector<float> cos_theta, phi;
  for (int i = 0; i < 2000; ++i) {
    cos_theta.push_back(uni(rng));
    phi.push_back(6.2831853f * uni(rng));
  }
  // The horizon (theta = pi/2, x = -1), just above it, the pole (x = 1) and just below it, where recurrences in
  // x lose precision first.
  for (float c : {0.0f, 1e-7f, 1e-3f, 1.0f, 1.0f - 1e-7f, 0.999f}) {
    cos_theta.push_back(c);
    phi.push_back(1.234f);
  }
  std::vector<float> device = device_basis(cos_theta, phi);
  std::vector<float> host(HSH_MAX_COEFFICIENTS);
  double worst = 0.0;
  for (size_t i = 0; i < cos_theta.size(); ++i) {
    hsh_basis(cos_theta[i], phi[i], HSH_MAX_ORDER, host.data());
    for (int l = 0; l < HSH_MAX_ORDER; ++l)
      for (int m = -l; m <= l; ++m) {
        int k = hsh_index(l, m);
        double want = reference_hsh(l, m, cos_theta[i], phi[i]);
        // The basis reaches about sqrt((2l + 1) / pi) in magnitude; float evaluation keeps a few 1e-6 of that.
        double scale = std::sqrt((2.0 * l + 1.0) / std::numbers::pi);
        double err = std::max(std::abs(device[i * HSH_MAX_COEFFICIENTS + size_t(k)] - want),
                              std::abs(host[size_t(k)] - want)) / scale;
        worst = std::max(worst, err);
        ASSERT_LT(err, 1e-5) << "l " << l << " m " << m << " at cos(theta) " << cos_theta[i] << ", phi " << phi[i]
                             << ": device " << device[i * HSH_MAX_COEFFICIENTS + size_t(k)] << ", host " << host[size_t(k)]
                             << ", reference " << want;
        ASSERT_TRUE(std::isfinite(device[i * HSH_MAX_COEFFICIENTS + size_t(k)]));
      }
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

// The Gram matrix of all HSH_MAX_ORDER^2 functions over the hemisphere is the identity: in double for the reference
// (which checks the definition and the quadrature), and in float for the device's basis.
TEST(Hsh, OrthonormalOverTheHemisphereUpToTheHighestOrder) {
  HemisphereQuadrature q;
  std::vector<float> device = device_basis(q.cos_theta, q.phi);
  const int n = HSH_MAX_COEFFICIENTS;
  std::vector<double> reference(q.weight.size() * size_t(n));
  for (size_t i = 0; i < q.weight.size(); ++i)
    for (int l = 0; l < HSH_MAX_ORDER; ++l)
      for (int m = -l; m <= l; ++m)
        reference[i * size_t(n) + size_t(hsh_index(l, m))] = reference_hsh(l, m, q.cos_theta[i], q.phi[i]);
  double worst_reference = 0.0, worst_device = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = a; b < n; ++b) {
      double gram_reference = 0.0, gram_device = 0.0;
      for (size_t i = 0; i < q.weight.size(); ++i) {
        gram_reference += q.weight[i] * reference[i * size_t(n) + size_t(a)] * reference[i * size_t(n) + size_t(b)];
        gram_device += q.weight[i] * double(device[i * size_t(n) + size_t(a)]) * device[i * size_t(n) + size_t(b)];
      }
      double want = a == b ? 1.0 : 0.0;
      worst_reference = std::max(worst_reference, std::abs(gram_reference - want));
      worst_device = std::max(worst_device, std::abs(gram_device - want));
    }
  // The quadrature nodes are floats (cos theta, phi rounded), so even the double reference is orthonormal only to
  // float precision of the directions.
  EXPECT_LT(worst_reference, 1e-5) << "the definition or the quadrature is wrong";
  EXPECT_LT(worst_device, 1e-5) << "the device basis is not orthonormal";
}

// Projects L from M x N strata drawn as the record pass draws them (cosine-weighted and jittered within each stratum,
// the same counter-based random numbers), with the stratum-integrated basis of kernels/hsh.h.
template <typename Radiance>
std::vector<float> project_strata(int order, int rows, int columns, Radiance radiance) {
  std::vector<float> coefficients(size_t(order * order), 0.0f), row_integrals(HSH_MAX_COEFFICIENTS);
  std::vector<float> row_sums(size_t(2 * order - 1));
  std::vector<float> columns_table = hsh_column_table(order, unsigned(columns));
  uint32_t key = hash_u32(12345u);
  for (int j = 0; j < rows; ++j) {
    std::fill(row_sums.begin(), row_sums.end(), 0.0f);
    for (int k = 0; k < columns; ++k) {
      uint32_t s = uint32_t(j * columns + k);
      float sin2 = (float(j) + random01(key, s, 0)) / float(rows);
      float phi = 2.0f * RC_PI * (float(k) + random01(key, s, 1)) / float(columns);
      float l = radiance(std::sqrt(1.0f - sin2), phi);
      for (size_t m = 0; m < row_sums.size(); ++m)
        row_sums[m] += l * columns_table[(size_t(k) * row_sums.size() + m) * 5];  // COLUMN_PHI
    }
    hsh_row_integrals(j, rows, order, row_integrals.data());
    for (int deg = 0; deg < order; ++deg)
      for (int m = -deg; m <= deg; ++m)
        coefficients[size_t(hsh_index(deg, m))] +=
            row_integrals[size_t(hsh_index(deg, std::abs(m)))] * row_sums[size_t(order - 1 + m)];
  }
  return coefficients;
}

// The exact coefficients of L (by the quadrature of the orthonormality test, in double).
template <typename Radiance>
std::vector<double> exact_coefficients(int order, Radiance radiance) {
  HemisphereQuadrature q;
  std::vector<double> c(size_t(order * order), 0.0);
  for (size_t i = 0; i < q.weight.size(); ++i)
    for (int l = 0; l < order; ++l)
      for (int m = -l; m <= l; ++m)
        c[size_t(hsh_index(l, m))] +=
            q.weight[i] * radiance(q.cos_theta[i], q.phi[i]) * reference_hsh(l, m, q.cos_theta[i], q.phi[i]);
  return c;
}

template <typename Radiance>
double projection_error(int order, int rows, int columns, Radiance radiance) {
  std::vector<double> want = exact_coefficients(order, radiance);
  std::vector<float> got = project_strata(order, rows, columns, radiance);
  double norm = 0.0, err = 0.0;
  for (size_t k = 0; k < want.size(); ++k) {
    norm += want[k] * want[k];
    err += (got[k] - want[k]) * (got[k] - want[k]);
  }
  return std::sqrt(err / norm);
}

// Projection from a record's strata (issue 9): a constant projects exactly (all of it in H_0^0 = sqrt(2 pi)), where
// weighting each ray by its stratum's solid angle left 17% error at 32 x 64; cos(theta) and a smooth off-axis lobe
// converge as the strata multiply; the sum lambda H reproduces the lobe.
TEST(Hsh, ProjectionFromRecordStrata) {
  const int order = 6;
  auto constant = [](float, float) { return 1.0f; };
  auto cosine = [](float c, float) { return c; };
  auto lobe = [](float c, float phi) {  // (omega . d)^8 about d at 30 degrees from the normal, zero behind it
    float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
    float d = c * 0.8660254f + s * std::cos(phi - 1.0f) * 0.5f;
    return d > 0.0f ? std::pow(d, 8.0f) : 0.0f;
  };
  std::vector<float> flat = project_strata(order, 8, 16, constant);
  EXPECT_NEAR(flat[0], std::sqrt(2.0 * std::numbers::pi), 1e-5);
  for (size_t k = 1; k < flat.size(); ++k) EXPECT_NEAR(flat[k], 0.0f, 2e-5f) << "coefficient " << k;
  double cosine_coarse = projection_error(order, 8, 16, cosine), cosine_fine = projection_error(order, 32, 64, cosine);
  double lobe_coarse = projection_error(order, 8, 16, lobe), lobe_default = projection_error(order, 16, 32, lobe);
  double lobe_fine = projection_error(order, 32, 64, lobe);
  // Measured (PoCL-independent, host arithmetic, fixed random numbers): cos(theta) 13.6% at 8 x 16 and 3.8% at
  // 32 x 64; the lobe 6.9%, 2.5% and 0.58% at 8 x 16, 16 x 32, 32 x 64. The error is the radiance's variation
  // inside a stratum around the jittered sample, first order in the stratum's size; the bounds leave 1.5x margin.
  EXPECT_LT(cosine_fine, 0.06);
  EXPECT_LT(cosine_fine, cosine_coarse / 2.0);
  EXPECT_LT(lobe_default, 0.04);
  EXPECT_LT(lobe_fine, 0.01);
  EXPECT_LT(lobe_fine, lobe_default);
  EXPECT_LT(lobe_default, lobe_coarse);
  RecordProperty("errors", "cos " + std::to_string(cosine_coarse) + " " + std::to_string(cosine_fine) + "; lobe " +
                               std::to_string(lobe_coarse) + " " + std::to_string(lobe_default) + " " +
                               std::to_string(lobe_fine));
  std::printf("projection error: cos(theta) %.2e (8x16) %.2e (32x64); lobe %.2e (8x16) %.2e (16x32) %.2e (32x64)\n",
              cosine_coarse, cosine_fine, lobe_coarse, lobe_default, lobe_fine);

  // The lobe rebuilt from the default 16 x 32 projection against the lobe rebuilt from the exact coefficients: the
  // projection's own error, apart from the truncation to order 6 that both share.
  std::vector<float> projected = project_strata(order, 16, 32, lobe);
  std::vector<double> exact = exact_coefficients(order, lobe);
  std::vector<float> exact_f(exact.begin(), exact.end());
  for (float cos_theta : {0.95f, 0.7f, 0.4f, 0.1f})
    for (float phi : {0.0f, 1.0f, 2.5f, 4.0f})
      EXPECT_NEAR(hsh_evaluate(projected.data(), order, cos_theta, phi), hsh_evaluate(exact_f.data(), order, cos_theta, phi),
                  0.02f)
          << "cos(theta) " << cos_theta << ", phi " << phi;
}

}  // namespace
}  // namespace rcsplat
