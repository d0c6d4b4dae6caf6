#include "passes/hsh_record_pass.h"

#include <algorithm>
#include <bit>

#include "cache/hsh_rotation.h"
#include "kernels/hsh.h"
#include "util/error.h"

namespace rcsplat {
namespace {

size_t floats_per_record(int order) { return size_t(HSH_RECORD_PARTS) * 3 * size_t(order) * size_t(order); }

}  // namespace

HshRecordPass::HshRecordPass(GpuContext& gpu, int order)
    : gpu_(gpu),
      order_(order),
      project_(gpu.kernel("hsh_records.cl", "project_radiance_records")),
      tilt_(gpu.kernel("hsh_records.cl", "tilt_radiance_records")) {
  if (order < 1 || order > HSH_MAX_ORDER)
    throw Error("--hsh-order must be between 1 and " + std::to_string(HSH_MAX_ORDER));
  const HshRotationDerivatives& d = hsh_rotation_derivatives(order);
  tilt_x_ = gpu_.upload(d.dx);
  tilt_y_ = gpu_.upload(d.dy);
  largest_bits_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE);
  reserve(256);
}

void HshRecordPass::reserve(size_t records) {
  if (records <= capacity_) return;
  size_t grown = std::max(records, capacity_ * 2);
  cl::Buffer bigger(gpu_.context(), CL_MEM_READ_WRITE, grown * floats_per_record(order_) * sizeof(float));
  if (capacity_)
    gpu_.queue().enqueueCopyBuffer(coefficients_, bigger, 0, 0, capacity_ * floats_per_record(order_) * sizeof(float));
  coefficients_ = bigger;
  capacity_ = grown;
}

void HshRecordPass::project(const cl::Buffer& strata, uint32_t first, uint32_t count, unsigned theta_strata,
                            unsigned phi_strata) {
  if (count == 0) return;
  reserve(size_t(first) + count);
  HshRecordParams params{};
  params.first_record = first;
  params.record_count = count;
  params.order = cl_uint(order_);
  params.theta_strata = theta_strata;
  params.phi_strata = phi_strata;
  project_.set_buffer<cl_float4>("strata", strata)
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

float HshRecordPass::largest_radiance() {
  return std::bit_cast<float>(gpu_.download<cl_uint>(largest_bits_, 1)[0]);
}

std::vector<float> HshRecordPass::download(uint32_t first, uint32_t count) {
  size_t per = floats_per_record(order_);
  std::vector<float> out(size_t(count) * per);
  if (count)
    gpu_.queue().enqueueReadBuffer(coefficients_, CL_TRUE, size_t(first) * per * sizeof(float),
                                   out.size() * sizeof(float), out.data());
  return out;
}

}  // namespace rcsplat
