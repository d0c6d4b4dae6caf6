#include "passes/splat_pass.h"

#include <bit>
#include <cmath>

#include "passes/ray_cast_pass.h"

namespace rcsplat {

SplatPass::SplatPass(GpuContext& gpu) : gpu_(gpu) {
  cl::Program& program = gpu_.program("splat.cl");
  clear_ = cl::Kernel(program, "clear_accumulators");
  max_irradiance_ = cl::Kernel(program, "max_record_irradiance");
  splat_ = cl::Kernel(program, "splat_records");
  resolve_ = cl::Kernel(program, "resolve_indirect");
  max_bits_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE);
}

void SplatPass::splat_all(const GBufferPass& gbuffer, const cl::Buffer& records, uint32_t count, float accuracy) {
  cl::CommandQueue& queue = gpu_.queue();
  if (gbuffer.pixel_count() != pixels_) {
    pixels_ = gbuffer.pixel_count();
    sums_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, pixels_ * 4 * sizeof(cl_long));
    counts_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, pixels_ * sizeof(cl_uint));
    for (cl::Buffer* b : {&irradiance_, &indirect_, &color_})
      *b = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, pixels_ * 4 * sizeof(float));
  }
  clear_.setArg(0, sums_);
  clear_.setArg(1, counts_);
  clear_.setArg(2, cl_uint(pixels_));
  queue.enqueueNDRangeKernel(clear_, cl::NullRange, cl::NDRange(round_up(pixels_, 64)), cl::NDRange(64));

  // The fixed-point unit comes from the frame's range: no extrapolated value exceeds (3 + a) times the largest record
  // component (the gradients are bounded), so that is the scale at which sums cannot overflow.
  queue.enqueueFillBuffer(max_bits_, cl_uint(0), 0, sizeof(cl_uint));
  if (count) {
    max_irradiance_.setArg(0, records);
    max_irradiance_.setArg(1, cl_uint(count));
    max_irradiance_.setArg(2, max_bits_);
    queue.enqueueNDRangeKernel(max_irradiance_, cl::NullRange, cl::NDRange(round_up(count, 64)), cl::NDRange(64));
  }
  float largest = std::bit_cast<float>(gpu_.download<cl_uint>(max_bits_, 1)[0]);
  params_.accuracy = accuracy;
  params_.irradiance_scale = std::isfinite(largest) && largest > 0.0f ? largest * (3.0f + accuracy) : 1.0f;
  params_.first_record = 0;
  params_.record_count = count;
  launch_splat(gbuffer, records);
}

void SplatPass::splat_more(const GBufferPass& gbuffer, const cl::Buffer& records, uint32_t first, uint32_t count) {
  params_.first_record = first;
  params_.record_count = count;
  launch_splat(gbuffer, records);
}

void SplatPass::launch_splat(const GBufferPass& gbuffer, const cl::Buffer& records) {
  if (params_.record_count) {
    int a = 0;
    splat_.setArg(a++, records);
    splat_.setArg(a++, params_);
    splat_.setArg(a++, gbuffer.samples());
    splat_.setArg(a++, gbuffer.camera());
    splat_.setArg(a++, sums_);
    splat_.setArg(a++, counts_);
    gpu_.queue().enqueueNDRangeKernel(splat_, cl::NullRange, cl::NDRange(round_up(params_.record_count, 8)),
                                      cl::NDRange(8));
  }
  gpu_.queue().finish();
}

void SplatPass::resolve(const GBufferPass& gbuffer, const cl::Buffer& direct_rgba) {
  int a = 0;
  resolve_.setArg(a++, sums_);
  resolve_.setArg(a++, params_);
  resolve_.setArg(a++, gbuffer.samples());
  resolve_.setArg(a++, direct_rgba);
  resolve_.setArg(a++, cl_uint(pixels_));
  resolve_.setArg(a++, irradiance_);
  resolve_.setArg(a++, indirect_);
  resolve_.setArg(a++, color_);
  gpu_.queue().enqueueNDRangeKernel(resolve_, cl::NullRange, cl::NDRange(round_up(pixels_, 64)), cl::NDRange(64));
  gpu_.queue().finish();
}

std::vector<float> SplatPass::irradiance_rgbw() { return gpu_.download<float>(irradiance_, pixels_ * 4); }
std::vector<float> SplatPass::indirect_rgba() { return gpu_.download<float>(indirect_, pixels_ * 4); }
std::vector<float> SplatPass::color_rgba() { return gpu_.download<float>(color_, pixels_ * 4); }
std::vector<uint32_t> SplatPass::records_per_pixel() { return gpu_.download<uint32_t>(counts_, pixels_); }

}  // namespace rcsplat
