// Hemispherical harmonics (kernels/hsh.h), compiled for the device and the host: against an independent
// double-precision reference built on std::assoc_legendre, orthonormal over the hemisphere up to the highest order
// offered (by Gauss-Legendre quadrature, exact for these polynomials), and stable at theta = pi/2 and at the pole.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/hsh.h"
#include "test_support.h"

namespace rcsplat {
namespace {

// H_l^m in double, from the definition (ALGORITHM.md section 6), written apart from kernels/hsh.h.
double reference_hsh(int l, int m, double cos_theta, double phi) {
  int am = std::abs(m);
  double x = 2.0 * cos_theta - 1.0;
  double k = std::sqrt((2.0 * l + 1.0) / (2.0 * std::numbers::pi) *
                       std::exp(std::lgamma(l - am + 1.0) - std::lgamma(l + am + 1.0)));
  double p = std::assoc_legendre(unsigned(l), unsigned(am), x);  // no Condon-Shortley phase, as hsh.h
  if (m == 0) return k * p;
  return std::sqrt(2.0) * k * p * (m > 0 ? std::cos(m * phi) : std::sin(am * phi));
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre polynomial).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.resize(size_t(n));
  weights.resize(size_t(n));
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    nodes[size_t(i)] = x;
    weights[size_t(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
}

// Directions of a quadrature over the hemisphere exact for products of two basis functions up to HSH_MAX_ORDER:
// Gauss-Legendre in x = 2 cos(theta) - 1 (d omega = dx dphi / 2) and equal steps in phi.
struct HemisphereQuadrature {
  std::vector<float> cos_theta, phi;
  std::vector<double> weight;
  HemisphereQuadrature() {
    std::vector<double> x, w;
    gauss_legendre(HSH_MAX_ORDER + 2, x, w);
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

}  // namespace
}  // namespace rcsplat
