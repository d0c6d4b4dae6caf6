#include "passes/path_pass.h"

#include <algorithm>
#include <cmath>

namespace rcsplat {
void PathPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) { gpu.build_ahead(kProgram, scene.defines()); }

PathPass::PathPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "path_indirect", scene.defines())) {
  ray_total_ = gpu_.upload(std::vector<cl_ulong>{0}, CL_MEM_READ_WRITE, "ray counter");
}

void PathPass::begin(const GBufferView& gbuffer, unsigned total_samples, bool stratified, unsigned seed,
                     unsigned bounces) {
  bounces_ = bounces;
  gbuffer_ = gbuffer;
  // The sums are kept while the frame's size is (a pass kept across frames, render/indirect.h) and cleared.
  if (!sum_() || gbuffer.pixel_count() != pixels_) {
    pixels_ = gbuffer.pixel_count();
    const size_t bytes = std::max<size_t>(pixels_, 1) * sizeof(cl_float4);
    sum_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "path sums");
    sum_squares_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "path sums");
  }
  if (pixels_) {
    gpu_.queue().enqueueFillBuffer(sum_, cl_float4{{0, 0, 0, 0}}, 0, pixels_ * sizeof(cl_float4));
    gpu_.queue().enqueueFillBuffer(sum_squares_, cl_float4{{0, 0, 0, 0}}, 0, pixels_ * sizeof(cl_float4));
  }
  gpu_.queue().enqueueFillBuffer(ray_total_, cl_ulong(0), 0, sizeof(cl_ulong));
  total_ = total_samples;
  done_ = 0;
  grid_side_ = stratified ? unsigned(std::sqrt(double(total_samples))) : 0;
  seed_ = seed;
}

void PathPass::add_samples(unsigned count) {
  count = std::min(count, total_ - done_);
  if (!count || !pixels_) return;
  PathParams params{};
  params.first_sample = done_;
  params.sample_count = count;
  params.grid_side = grid_side_;
  params.seed = seed_;
  params.bounces = bounces_;
  scene_.bind(kernel_);
  gbuffer_.bind(kernel_);
  gbuffer_.bind_see_through(kernel_);
  kernel_.set("params", params)
      .set_buffer<cl_float4>("sum", sum_)
      .set_buffer<cl_float4>("sum_squares", sum_squares_)
      .set_buffer<cl_ulong>("ray_total", ray_total_);
  kernel_.launch(pixels_, gpu_.groups().traversal);
  gpu_.queue().finish();
  done_ += count;
}

std::vector<float> PathPass::mean_rgb(std::vector<float>* variance) {
  const std::vector<float> sum = gpu_.download<float>(sum_, pixels_ * 4);
  std::vector<float> rgb(pixels_ * 3, 0.0f);
  if (done_)
    for (size_t i = 0; i < pixels_; ++i)
      for (size_t c = 0; c < 3; ++c) rgb[3 * i + c] = sum[4 * i + c] / float(done_);
  if (!variance) return rgb;
  variance->assign(pixels_ * 3, 0.0f);
  if (done_ < 2) return rgb;
  const std::vector<float> squares = gpu_.download<float>(sum_squares_, pixels_ * 4);
  const double n = done_;
  for (size_t i = 0; i < pixels_; ++i)
    for (size_t c = 0; c < 3; ++c) {
      double mean = sum[4 * i + c] / n;
      double sample_var = std::max(0.0, (squares[4 * i + c] / n - mean * mean) * n / (n - 1));
      (*variance)[3 * i + c] = float(sample_var / n);
    }
  return rgb;
}

uint64_t PathPass::rays_cast() { return gpu_.download<cl_ulong>(ray_total_, 1)[0]; }

}  // namespace rcsplat
