#include "passes/splat_pass.h"

#include <bit>

#include "kernels/cache_math.h"

namespace rcsplat {
void SplatPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }

SplatPass::SplatPass(GpuContext& gpu)
    : gpu_(gpu),
      clear_(gpu.kernel(kProgram, "clear_accumulators")),
      max_irradiance_(gpu.kernel(kProgram, "max_record_irradiance")),
      splat_(gpu.kernel(kProgram, "splat_records")),
      resolve_(gpu.kernel(kProgram, "resolve_indirect")),
      fill_(gpu.kernel(kProgram, "fill_uncovered")) {
  max_bits_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, "splat sums");
  filled_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, "splat sums");
}

void SplatPass::splat_all(const GBufferView& gbuffer, const cl::Buffer& records, uint32_t count, float accuracy) {
  cl::CommandQueue& queue = gpu_.queue();
  const GroupSizes& groups = gpu_.groups();
  if (gbuffer.pixel_count() != pixels_ || !sums_()) {
    pixels_ = gbuffer.pixel_count();
    size_t slots = std::max<size_t>(pixels_, 1);
    sums_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * 4 * sizeof(cl_long), "splat sums");
    counts_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * sizeof(cl_uint), "splat counts");
    irradiance_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * 4 * sizeof(float), "splat irradiance");
  }
  gbuffer.bind(clear_);
  clear_.set_buffer<cl_long>("sums", sums_).set_buffer<cl_uint>("counts", counts_);
  clear_.launch(pixels_, groups.per_item);

  params_ = SplatParams{};
  params_.accuracy = accuracy;
  params_.first_record = 0;
  params_.record_count = count;
  queue.enqueueFillBuffer(max_bits_, cl_uint(0), 0, sizeof(cl_uint));
  max_irradiance_.set_buffer<CacheRecord>("records", records).set("params", params_).set_buffer<cl_uint>("max_bits", max_bits_);
  max_irradiance_.launch(count, groups.per_item);
  float largest = std::bit_cast<float>(gpu_.download<cl_uint>(max_bits_, 1)[0]);
  params_.irradiance_scale = fixed_point_irradiance_scale(largest, accuracy);

  gbuffer.bind(splat_);
  splat_.set_buffer<CacheRecord>("records", records)
      .set("params", params_)
      .set_buffer<cl_long>("sums", sums_)
      .set_buffer<cl_uint>("counts", counts_);
  splat_.launch(count, groups.per_record);
  queue.finish();
}

void SplatPass::resolve(const GBufferView& gbuffer) {
  gbuffer.bind(resolve_);
  resolve_.set_buffer<cl_long>("sums", sums_).set("params", params_).set_buffer<cl_float4>("irradiance_out", irradiance_);
  resolve_.launch(pixels_, gpu_.groups().per_item);
  gpu_.queue().finish();
}

uint32_t SplatPass::fill_uncovered(const GBufferView& gbuffer, const cl::Buffer& records,
                                   const cl::Buffer& record_at_pixel, int window) {
  gpu_.queue().enqueueFillBuffer(filled_, cl_uint(0), 0, sizeof(cl_uint));
  gbuffer.bind(fill_);
  fill_.set_buffer<CacheRecord>("records", records)
      .set_buffer<cl_int>("record_at_pixel", record_at_pixel)
      .set("window", cl_int(window))
      .set_buffer<cl_float4>("irradiance_out", irradiance_)
      .set_buffer<cl_uint>("filled", filled_);
  fill_.launch(pixels_, gpu_.groups().per_item);
  return gpu_.download<cl_uint>(filled_, 1)[0];
}

std::vector<float> SplatPass::irradiance_rgbw() { return gpu_.download<float>(irradiance_, pixels_ * 4); }
std::vector<uint32_t> SplatPass::records_per_pixel() { return gpu_.download<uint32_t>(counts_, pixels_); }

}  // namespace rcsplat
