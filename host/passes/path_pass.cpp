#include "passes/path_pass.h"

#include <cmath>

#include "passes/ray_cast_pass.h"

namespace rcsplat {

PathPass::PathPass(GpuContext& gpu, const DeviceScene& scene) : gpu_(gpu), scene_(scene) {
  kernel_ = cl::Kernel(gpu_.program("path.cl", scene_.defines()), "path_indirect");
  ray_total_ = gpu_.upload(std::vector<cl_ulong>{0}, CL_MEM_READ_WRITE);
}

void PathPass::begin(const GBufferPass& gbuffer, unsigned total_samples, bool stratified, unsigned seed) {
  gbuffer_ = &gbuffer;
  pixels_ = gbuffer.pixel_count();
  std::vector<cl_float4> zeros(pixels_, cl_float4{{0, 0, 0, 0}});
  sum_ = gpu_.upload(zeros, CL_MEM_READ_WRITE);
  sum_squares_ = gpu_.upload(zeros, CL_MEM_READ_WRITE);
  gpu_.queue().enqueueFillBuffer(ray_total_, cl_ulong(0), 0, sizeof(cl_ulong));
  total_ = total_samples;
  done_ = 0;
  grid_side_ = stratified ? unsigned(std::sqrt(double(total_samples))) : 0;
  seed_ = seed;
}

void PathPass::add_samples(unsigned count) {
  count = std::min(count, total_ - done_);
  if (!count || !pixels_) return;
  cl_uint a = scene_.bind_shading_args(kernel_, 0);
  kernel_.setArg(a++, gbuffer_->samples());
  kernel_.setArg(a++, cl_uint(pixels_));
  kernel_.setArg(a++, cl_uint(done_));
  kernel_.setArg(a++, cl_uint(count));
  kernel_.setArg(a++, cl_uint(grid_side_));
  kernel_.setArg(a++, cl_uint(seed_));
  kernel_.setArg(a++, sum_);
  kernel_.setArg(a++, sum_squares_);
  kernel_.setArg(a++, ray_total_);
  gpu_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(round_up(pixels_, kTraversalLocalSize)),
                                    cl::NDRange(kTraversalLocalSize));
  gpu_.queue().finish();
  done_ += count;
}

std::vector<float> PathPass::mean_rgb() {
  std::vector<float> sum = gpu_.download<float>(sum_, pixels_ * 4), rgb(pixels_ * 3, 0.0f);
  if (!done_) return rgb;
  for (size_t i = 0; i < pixels_; ++i)
    for (size_t c = 0; c < 3; ++c) rgb[3 * i + c] = sum[4 * i + c] / float(done_);
  return rgb;
}

std::vector<float> PathPass::mean_variance_rgb() {
  std::vector<float> sum = gpu_.download<float>(sum_, pixels_ * 4);
  std::vector<float> squares = gpu_.download<float>(sum_squares_, pixels_ * 4), var(pixels_ * 3, 0.0f);
  if (done_ < 2) return var;
  double n = done_;
  for (size_t i = 0; i < pixels_; ++i)
    for (size_t c = 0; c < 3; ++c) {
      double mean = sum[4 * i + c] / n;
      double sample_var = std::max(0.0, (squares[4 * i + c] / n - mean * mean) * n / (n - 1));
      var[3 * i + c] = float(sample_var / n);
    }
  return var;
}

uint64_t PathPass::rays_cast() { return gpu_.download<cl_ulong>(ray_total_, 1)[0]; }

}  // namespace rcsplat
