#include "passes/hsh_record_pass.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "cache/hsh_rotation.h"
#include "kernels/hsh.h"
#include "util/error.h"

namespace rcsplat {
void HshRecordPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }
namespace {

size_t floats_per_order(int order) { return size_t(HSH_RECORD_PARTS) * 3 * size_t(order) * size_t(order); }

// The integrals of cos(a phi) and sin(a phi) over [phi0, phi1], for an integer a >= 0.
double integral_cos(int a, double phi0, double phi1) {
  return a == 0 ? phi1 - phi0 : (std::sin(a * phi1) - std::sin(a * phi0)) / a;
}
double integral_sin(int a, double phi0, double phi1) {
  return a == 0 ? 0.0 : (std::cos(a * phi0) - std::cos(a * phi1)) / a;
}

}  // namespace

// With f_m the azimuthal factor (sqrt(2) cos(m phi), 1, sqrt(2) sin(|m| phi)), the products with cos phi and sin phi
// are integrated by their sums and differences.
std::vector<float> hsh_column_table(int order, unsigned columns) {
  const double pi = std::numbers::pi, root2 = std::sqrt(2.0);
  std::vector<float> table;
  for (unsigned k = 0; k < columns; ++k) {
    double phi0 = 2.0 * pi * k / columns, phi1 = 2.0 * pi * (k + 1) / columns;
    for (int m = -(order - 1); m < order; ++m) {
      int a = std::abs(m);
      double phi, wall_t, wall_b, at_wall;
      if (m == 0) {
        phi = phi1 - phi0;
        wall_t = integral_cos(1, phi0, phi1);
        wall_b = integral_sin(1, phi0, phi1);
        at_wall = 1.0;
      } else if (m > 0) {  // cos(phi) cos(m phi), sin(phi) cos(m phi)
        phi = root2 * integral_cos(a, phi0, phi1);
        wall_t = root2 * 0.5 * (integral_cos(a - 1, phi0, phi1) + integral_cos(a + 1, phi0, phi1));
        wall_b = root2 * 0.5 * (integral_sin(a + 1, phi0, phi1) - integral_sin(a - 1, phi0, phi1));
        at_wall = root2 * std::cos(a * phi0);
      } else {  // cos(phi) sin(|m| phi), sin(phi) sin(|m| phi)
        phi = root2 * integral_sin(a, phi0, phi1);
        wall_t = root2 * 0.5 * (integral_sin(a + 1, phi0, phi1) + integral_sin(a - 1, phi0, phi1));
        wall_b = root2 * 0.5 * (integral_cos(a - 1, phi0, phi1) - integral_cos(a + 1, phi0, phi1));
        at_wall = root2 * std::sin(a * phi0);
      }
      for (double v : {phi, wall_t, wall_b, -std::sin(phi0) * at_wall, std::cos(phi0) * at_wall})
        table.push_back(float(v));
    }
  }
  return table;
}

HshRecordPass::HshRecordPass(GpuContext& gpu, int order)
    : gpu_(gpu),
      order_(order),
      project_(gpu.kernel(kProgram, "project_radiance_records")),
      tilt_(gpu.kernel(kProgram, "tilt_radiance_records")),
      bound_fitted_(gpu.kernel(kProgram, "bound_fitted_radiance_gradients")) {
  const HshRotationDerivatives& d = hsh_rotation_derivatives(order);
  tilt_x_ = gpu_.upload(d.dx, CL_MEM_READ_ONLY, "radiance records");
  tilt_y_ = gpu_.upload(d.dy, CL_MEM_READ_ONLY, "radiance records");
  largest_bits_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, "radiance records");
  reserve(256);
}

void HshRecordPass::reserve(size_t records) {
  gpu_.reserve(coefficients_, capacity_, records, floats_per_order(order_) * sizeof(float), "radiance records", true);
}

void HshRecordPass::project(const cl::Buffer& strata, const cl::Buffer& records, uint32_t first, uint32_t count,
                            unsigned theta_strata, unsigned phi_strata) {
  if (count == 0) return;
  reserve(size_t(first) + count);
  HshRecordParams params{};
  params.first_record = first;
  params.record_count = count;
  params.order = cl_uint(order_);
  params.theta_strata = theta_strata;
  params.phi_strata = phi_strata;
  if (phi_strata != table_columns_) {
    column_table_ = gpu_.upload(hsh_column_table(order_, phi_strata), CL_MEM_READ_ONLY, "radiance records");
    table_columns_ = phi_strata;
  }
  project_.set_buffer<cl_float4>("strata", strata)
      .set_buffer<cl_float>("column_table", column_table_)
      .set_buffer<CacheRecord>("records", records)
      .set("params", params)
      .set_buffer<cl_float>("coefficients", coefficients_)
      .set_buffer<cl_uint>("max_radiance_bits", largest_bits_);
  project_.launch(count, gpu_.groups().per_record);
  tilt_.set_buffer<cl_float>("tilt_x", tilt_x_)
      .set_buffer<cl_float>("tilt_y", tilt_y_)
      .set("params", params)
      .set_buffer<cl_float>("coefficients", coefficients_);
  tilt_.launch(size_t(count) * size_t(order_) * size_t(order_), 64);
  gpu_.queue().finish();
}

void HshRecordPass::begin_frame(float largest_kept) {
  // Radiance is not negative, so its bits order as unsigned integers (the kernel's atomic_max).
  gpu_.queue().enqueueFillBuffer(largest_bits_, std::bit_cast<cl_uint>(std::max(largest_kept, 0.0f)), 0,
                                 sizeof(cl_uint));
}

size_t HshRecordPass::floats_per_record() const { return rcsplat::floats_per_order(order_); }

void HshRecordPass::load(const std::vector<float>& coefficients, uint32_t count) {
  if (coefficients.size() != size_t(count) * floats_per_record())
    throw Error("radiance records: " + std::to_string(coefficients.size()) + " coefficients for " +
                std::to_string(count) + " records of order " + std::to_string(order_));
  if (count == 0) return;
  reserve(count);
  gpu_.queue().enqueueWriteBuffer(coefficients_, CL_TRUE, 0, coefficients.size() * sizeof(float), coefficients.data());
}

void HshRecordPass::bound_fitted_gradients(const cl::Buffer& records, const std::vector<float>& kept_radii) {
  if (kept_radii.empty()) return;
  if (kept_radii.size() > capacity_) throw Error("radiance records: more kept radii than loaded records");
  HshRecordParams params{};
  params.record_count = cl_uint(kept_radii.size());
  params.order = cl_uint(order_);
  const cl::Buffer radii = gpu_.upload(kept_radii, CL_MEM_READ_ONLY, "radiance records");
  bound_fitted_.set_buffer<CacheRecord>("records", records)
      .set_buffer<cl_float>("kept_radii", radii)
      .set("params", params)
      .set_buffer<cl_float>("coefficients", coefficients_);
  bound_fitted_.launch(kept_radii.size(), gpu_.groups().per_record);
  gpu_.queue().finish();
}

float HshRecordPass::largest_radiance() {
  return std::bit_cast<float>(gpu_.download<cl_uint>(largest_bits_, 1)[0]);
}

std::vector<float> HshRecordPass::download(uint32_t first, uint32_t count) {
  size_t per = floats_per_order(order_);
  std::vector<float> out(size_t(count) * per);
  if (count)
    gpu_.queue().enqueueReadBuffer(coefficients_, CL_TRUE, size_t(first) * per * sizeof(float),
                                   out.size() * sizeof(float), out.data());
  return out;
}

}  // namespace rcsplat
