#include "passes/radiance_splat_pass.h"

#include <algorithm>

namespace rcsplat {
void RadianceSplatPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }

RadianceSplatPass::RadianceSplatPass(GpuContext& gpu, const BrdfTable& table,
                                     const std::vector<int>& table_row_of_material)
    : gpu_(gpu),
      keep_(gpu.kernel(kProgram, "keep_radiance_cached_pixels")),
      clear_(gpu.kernel(kProgram, "clear_radiance_sums")),
      splat_(gpu.kernel(kProgram, "splat_radiance")),
      resolve_(gpu.kernel(kProgram, "resolve_radiance")),
      fill_(gpu.kernel(kProgram, "fill_uncovered_radiance")) {
  std::vector<float> lobe = table.lobe;
  if (lobe.empty()) lobe.push_back(0.0f);
  std::vector<int> rows = table_row_of_material;
  if (rows.empty()) rows.push_back(-1);
  table_ = gpu_.upload(lobe, CL_MEM_READ_ONLY, "radiance splat tables");
  table_rows_ = gpu_.upload(rows, CL_MEM_READ_ONLY, "radiance splat tables");
  filled_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, "radiance splat sums");
  params_.order = cl_uint(table.order);
  params_.angle_count = cl_uint(table.angle_count);
}

void RadianceSplatPass::size_for(const GBufferView& gbuffer) {
  if (gbuffer.pixel_count() == pixels_ && sums_()) return;
  pixels_ = gbuffer.pixel_count();
  size_t slots = std::max<size_t>(pixels_, 1);
  kept_samples_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * sizeof(GBufferSample), "radiance splat kept samples");
  sums_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * 4 * sizeof(cl_long), "radiance splat sums");
  lobe_radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * 4 * sizeof(float), "radiance splat lobe radiance");
}

const GBufferView& RadianceSplatPass::radiance_cached_pixels(const GBufferView& gbuffer) {
  size_for(gbuffer);
  gbuffer.bind(keep_);
  keep_.set_buffer<GBufferSample>("kept", kept_samples_);
  keep_.launch(pixels_, gpu_.groups().per_item);
  gpu_.queue().finish();
  kept_ = gbuffer;
  kept_.samples = kept_samples_;
  return kept_;
}

void RadianceSplatPass::splat_all(const GBufferView& gbuffer, const cl::Buffer& records,
                                  const cl::Buffer& coefficients, uint32_t count, float accuracy,
                                  float radiance_scale) {
  size_for(gbuffer);
  gbuffer.bind(clear_);
  clear_.set_buffer<cl_long>("sums", sums_);
  clear_.launch(pixels_, gpu_.groups().per_item);
  params_.accuracy = accuracy;
  params_.radiance_scale = radiance_scale > 0.0f ? radiance_scale : 1.0f;
  params_.record_count = count;
  if (count) {
    gbuffer.bind(splat_);
    splat_.set_buffer<CacheRecord>("records", records)
        .set_buffer<cl_float>("coefficients", coefficients)
        .set_buffer<cl_float>("lobe_table", table_)
        .set_buffer<cl_int>("table_row_of_material", table_rows_)
        .set("params", params_)
        .set_buffer<cl_long>("sums", sums_);
    splat_.launch(count, gpu_.groups().per_record);
  }
  gpu_.queue().finish();
}

void RadianceSplatPass::resolve(const GBufferView& gbuffer) {
  gbuffer.bind(resolve_);
  resolve_.set_buffer<cl_long>("sums", sums_).set("params", params_).set_buffer<cl_float4>("lobe_out", lobe_radiance_);
  resolve_.launch(pixels_, gpu_.groups().per_item);
  gpu_.queue().finish();
}

uint32_t RadianceSplatPass::fill_uncovered(const GBufferView& gbuffer, const cl::Buffer& records,
                                           const cl::Buffer& coefficients, const cl::Buffer& record_at_pixel,
                                           int window) {
  gpu_.queue().enqueueFillBuffer(filled_, cl_uint(0), 0, sizeof(cl_uint));
  gbuffer.bind(fill_);
  fill_.set_buffer<CacheRecord>("records", records)
      .set_buffer<cl_float>("coefficients", coefficients)
      .set_buffer<cl_float>("lobe_table", table_)
      .set_buffer<cl_int>("table_row_of_material", table_rows_)
      .set_buffer<cl_int>("record_at_pixel", record_at_pixel)
      .set("window", cl_int(window))
      .set("params", params_)
      .set_buffer<cl_float4>("lobe_out", lobe_radiance_)
      .set_buffer<cl_uint>("filled", filled_);
  fill_.launch(pixels_, gpu_.groups().per_item);
  return gpu_.download<cl_uint>(filled_, 1)[0];
}

std::vector<float> RadianceSplatPass::lobe_radiance_rgbw() { return gpu_.download<float>(lobe_radiance_, pixels_ * 4); }

}  // namespace rcsplat
