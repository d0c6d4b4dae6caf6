// A record's HSH coefficients turned into a pixel's frame on the device (kernels/hsh_frame.h: small-angle tilt
// through host/cache/hsh_rotation.h's derivative matrices, exact turn about the normal) against re-projection of the
// same radiance in the pixel's frame, in double: the reflected radiance sum_k lobe_k lambda_k must agree.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <random>
#include <vector>

#include "cache/hsh_rotation.h"
#include "kernels/hsh.h"
#include "kernels/shared_types.h"
#include "test_support.h"

namespace rcsplat {
namespace {

using glm::dvec3;

const char* kReflectThroughFrame = R"(
#include "hsh_frame.h"
__kernel void reflect_through_frame(__global const float* blocks, __global const float* lobes,
                                    __global const float* geometry, uint order, uint count, __global float* out) {
  uint i = get_global_id(0);
  if (i >= count) return;
  const int n2 = (int)(order * order);
  float3 nk = vload3(0, geometry + 9 * i), n = vload3(1, geometry + 9 * i), view = vload3(2, geometry + 9 * i);
  float3 tk, bk;
  tangent_frame(nk, &tk, &bk);
  HshFrameChange f = hsh_frame_change(nk, tk, bk, n, view);
  float a[HSH_MAX_COEFFICIENTS], b[HSH_MAX_COEFFICIENTS];
  for (int k = 0; k < n2; ++k) {
    a[k] = lobes[i * n2 + k];
    b[k] = 0.0f;
  }
  float3 r = hsh_reflected(blocks + (size_t)i * HSH_RECORD_PARTS * 3 * n2, (int)order, 0.0f, 0.0f, f, a, b,
                           (float3)(1.0f), (float3)(0.0f));
  out[i] = r.x;
}
)";

// The same frame the kernels build from a normal (kernels/host_device.h tangent_frame), in double.
void tangent_frame(dvec3 n, dvec3& t, dvec3& b) {
  double sign = n.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sign + n.z), c = n.x * n.y * a;
  t = dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = dvec3(c, sign + n.y * n.y * a, -n.y);
}

// lambda_k of radiance L (a function of the world direction) in the frame (t, b, n), by quadrature.
// The quadrature's directions (in any frame's own coordinates) and the basis there, computed once.
struct BasisTable {
  HemisphereQuadrature q = hemisphere_quadrature(48, 96);
  std::vector<double> basis;  // [point * HSH_MAX_COEFFICIENTS + k]
  BasisTable() {
    for (size_t i = 0; i < q.weight.size(); ++i) {
      double phi = std::atan2(q.y[i], q.x[i]);
      for (int deg = 0; deg < HSH_MAX_ORDER; ++deg)
        for (int m = -deg; m <= deg; ++m) basis.push_back(hsh_basis_double(deg, m, q.z[i], phi));
    }
  }
};

template <typename Radiance>
std::vector<double> project(const Radiance& radiance, dvec3 t, dvec3 b, dvec3 n, int order) {
  static const BasisTable table;
  const HemisphereQuadrature& q = table.q;
  std::vector<double> lambda(size_t(order * order), 0.0);
  for (size_t i = 0; i < q.weight.size(); ++i) {
    double wl = q.weight[i] * radiance(q.x[i] * t + q.y[i] * b + q.z[i] * n);
    for (size_t k = 0; k < lambda.size(); ++k) lambda[k] += wl * table.basis[i * HSH_MAX_COEFFICIENTS + k];
  }
  return lambda;
}

struct Case {
  dvec3 nk, n, view;
};

// For each case: the device's reflected radiance with the tilt (and without it, D_x = D_y = 0), and the re-projected
// one.
struct Outcome {
  std::vector<double> with_tilt, without_tilt, reprojected;
};

// Radiance over the whole sphere. Everywhere: a floor, a soft bright lobe and a linear drift, so that light arrives
// from just below the record's horizon too. Horizon-free: a lobe around the record's normal that vanishes toward
// its horizon.
Outcome run(const std::vector<Case>& cases, int order, bool horizon_free) {
  const int n2 = order * order;
  const HshRotationDerivatives& d = hsh_rotation_derivatives(order);
  dvec3 bright = glm::normalize(dvec3(0.4, -0.3, 0.8)), drift = glm::normalize(dvec3(-0.5, 0.7, 0.2));
  // Smooth radiance over the whole sphere: a soft bright lobe, a linear drift and a floor.
  dvec3 record_normal;
  auto radiance = [&](dvec3 w) {
    if (horizon_free) return std::exp(6.0 * (glm::dot(w, record_normal) - 1.0) + 3.0 * (glm::dot(w, bright) - 1.0));
    return 0.5 + 2.0 * std::exp(6.0 * (glm::dot(w, bright) - 1.0)) + 0.3 * glm::dot(w, drift);
  };
  std::vector<float> blocks, blocks_untilted, lobes, geometry;
  Outcome out;
  for (const Case& c : cases) {
    dvec3 t, b;
    record_normal = c.nk;
    tangent_frame(c.nk, t, b);
    std::vector<double> lambda = project(radiance, t, b, c.nk, order);
    std::vector<float> block(size_t(HSH_RECORD_PARTS * 3 * n2), 0.0f);
    for (int k = 0; k < n2; ++k) {
      double tx = 0.0, ty = 0.0;
      for (int j = 0; j < n2; ++j) {
        tx += d.dx[size_t(k * n2 + j)] * lambda[size_t(j)];
        ty += d.dy[size_t(k * n2 + j)] * lambda[size_t(j)];
      }
      for (int ch = 0; ch < 3; ++ch) {
        block[size_t(3 * (HSH_PART_COEFFICIENTS * n2 + k) + ch)] = float(lambda[size_t(k)]);
        block[size_t(3 * (HSH_PART_TILT_X * n2 + k) + ch)] = float(tx);
        block[size_t(3 * (HSH_PART_TILT_Y * n2 + k) + ch)] = float(ty);
      }
    }
    blocks.insert(blocks.end(), block.begin(), block.end());
    for (int k = 0; k < 3 * n2; ++k) block[size_t(3 * HSH_PART_TILT_X * n2 + k)] = block[size_t(3 * HSH_PART_TILT_Y * n2 + k)] = 0.0f;
    blocks_untilted.insert(blocks_untilted.end(), block.begin(), block.end());
    // The pixel's frame: x along the view's azimuth. A glossy lobe around the view's reflection, projected there.
    dvec3 tp = glm::normalize(c.view - c.n * glm::dot(c.n, c.view)), bp = glm::cross(c.n, tp);
    double cos_o = glm::dot(c.n, c.view);
    dvec3 mirror = -glm::dot(c.view, tp) * tp + cos_o * c.n;
    auto lobe = [&](dvec3 w) { return std::exp(5.0 * (glm::dot(w, mirror) - 1.0)); };
    std::vector<double> lobe_k = project(lobe, tp, bp, c.n, order), lambda_p = project(radiance, tp, bp, c.n, order);
    double want = 0.0;
    for (int deg = 0; deg < order; ++deg)
      for (int m = 0; m <= deg; ++m) {  // the lobe is even in the pixel's y: no sin(m phi) part
        int k = hsh_index(deg, m);
        want += lobe_k[size_t(k)] * lambda_p[size_t(k)];
      }
    for (int deg = 0; deg < order; ++deg)
      for (int m = -deg; m <= deg; ++m) lobes.push_back(m >= 0 ? float(lobe_k[size_t(hsh_index(deg, m))]) : 0.0f);
    out.reprojected.push_back(want);
    for (dvec3 v : {c.nk, c.n, c.view})
      for (int a = 0; a < 3; ++a) geometry.push_back(float(v[a]));
  }
  GpuContext& gpu = test::gpu();
  NamedKernel kernel(gpu, gpu.program_from_text("hsh_rotation_test.cl", kReflectThroughFrame), "reflect_through_frame");
  cl::Buffer lobe_buffer = gpu.upload(lobes), geometry_buffer = gpu.upload(geometry);
  for (std::vector<float>* source : {&blocks, &blocks_untilted}) {
    cl::Buffer result(gpu.context(), CL_MEM_WRITE_ONLY, cases.size() * sizeof(float));
    cl::Buffer block_buffer = gpu.upload(*source);
    kernel.set_buffer<cl_float>("blocks", block_buffer)
        .set_buffer<cl_float>("lobes", lobe_buffer)
        .set_buffer<cl_float>("geometry", geometry_buffer)
        .set("order", cl_uint(order))
        .set("count", cl_uint(cases.size()))
        .set_buffer<cl_float>("out", result);
    kernel.launch(cases.size(), 1);
    gpu.queue().finish();
    std::vector<float> got = gpu.download<float>(result, cases.size());
    (source == &blocks ? out.with_tilt : out.without_tilt).assign(got.begin(), got.end());
  }
  return out;
}

// Random record normals, pixel normals tilted from them by `degrees` about a random axis, random views above the pixel.
std::vector<Case> cases_at(double degrees, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  std::vector<Case> cases;
  while (cases.size() < 16) {
    dvec3 nk = glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng)));
    dvec3 axis = glm::normalize(glm::cross(nk, dvec3(gauss(rng), gauss(rng), gauss(rng))));
    double a = degrees * 3.14159265358979 / 180.0;
    dvec3 n = glm::normalize(nk * std::cos(a) + glm::cross(axis, nk) * std::sin(a));
    dvec3 view = glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng)));
    if (glm::dot(view, n) < 0.2) continue;
    cases.push_back({nk, n, view});
  }
  return cases;
}

double mean_relative_error(const std::vector<double>& got, const std::vector<double>& want) {
  double sum = 0.0;
  for (size_t i = 0; i < got.size(); ++i) sum += std::abs(got[i] - want[i]) / want[i];
  return sum / double(got.size());
}

// The normals of a pixel and a usable radiance record are at most about 12 degrees apart at the default radiance
// accuracy (a = 0.15: sqrt(1 - cos) < a), 24 at a = 0.3. Measured (order 10, 16 cases each, mean relative error
// with the tilt / without it): radiance from everywhere 1.1e-2 / 2.4e-2 at 5 degrees, 2.6e-2 / 6.7e-2 at 12,
// 3.9e-2 / 1.2e-1 at 24; horizon-free 6.5e-3 / 1.2e-1 at 5, 5.4e-2 / 3.2e-1 at 12. Horizon-free the tilt's error grows
// as the angle squared (first order is right); with light from just below the record's horizon it grows linearly:
// that light is in the pixel's hemisphere but was never in the record's, and no rotation can supply it.
TEST(HshRotation, SmallAngleTiltAgreesWithReprojectionInThePixelsFrame) {
  const int order = HSH_MAX_ORDER;
  for (bool horizon_free : {false, true}) {
    std::vector<double> tilted, untilted;
    for (double degrees : {0.0, 5.0, 12.0, 24.0}) {
      Outcome o = run(cases_at(degrees, 11 + unsigned(degrees)), order, horizon_free);
      tilted.push_back(mean_relative_error(o.with_tilt, o.reprojected));
      untilted.push_back(mean_relative_error(o.without_tilt, o.reprojected));
      std::printf("%s, normals %4.1f degrees apart: mean relative error %.2e with the tilt, %.2e without\n",
                  horizon_free ? "horizon-free radiance" : "radiance from everywhere", degrees, tilted.back(),
                  untilted.back());
    }
    EXPECT_LT(tilted[0], 1e-5);  // no tilt: the turn about the normal alone, exact up to float
    for (size_t i = 1; i < tilted.size(); ++i) EXPECT_LT(tilted[i], 0.6 * untilted[i]) << "angle " << i;
    if (horizon_free) {
      EXPECT_LT(tilted[1], 0.015);
      EXPECT_LT(tilted[2], 0.2 * untilted[2]);
    } else {
      EXPECT_LT(tilted[2], 0.035);
    }
  }
}

}  // namespace
}  // namespace rcsplat
