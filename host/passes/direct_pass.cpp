#include "passes/direct_pass.h"

#include <algorithm>

#include "passes/sample_rounds.h"

namespace rcsplat {
void DirectPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) { gpu.build_ahead(kProgram, scene.defines()); }

DirectPass::DirectPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu),
      scene_(scene),
      kernel_(gpu.kernel(kProgram, "direct_light", scene.defines())) {
  // The rounds' kernels exist only where the scene samples lights (kernels/direct.cl).
  if (samples_lights()) {
    round_ = gpu.kernel(kProgram, "direct_light_round", scene.defines());
    pixel_error_ = gpu.kernel(kProgram, "direct_pixel_error", scene.defines());
    average_ = gpu.kernel(kProgram, "average_direct_samples", scene.defines());
  }
}

bool DirectPass::samples_lights() const {
  return !scene_.emitters().empty() || scene_.environment_peak_power() > 0.0f;
}

DirectRunStats DirectPass::run(const GBufferView& gbuffer, unsigned strata_per_axis, unsigned seed,
                               unsigned light_budget) {
  if (gbuffer.pixel_count() != pixels_ || !radiance_()) {
    pixels_ = gbuffer.pixel_count();
    const size_t bytes = std::max<size_t>(pixels_, 1) * sizeof(cl_float4);
    radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "direct radiance");
    sums_ = moments_ = cl::Buffer();
  }
  if (light_budget > 0 && samples_lights() && strata_per_axis > 0) return run_rounds(gbuffer, seed, light_budget);
  DirectParams params{};
  params.strata_per_axis = strata_per_axis;
  params.seed = seed;
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set("params", params).set_buffer<cl_float4>("direct_out", radiance_);
  kernel_.launch(pixels_, gpu_.groups().traversal);
  gpu_.queue().finish();
  return {};
}

void DirectPass::run_round(const GBufferView& gbuffer, const DirectParams& params, size_t item_count) {
  scene_.bind(round_);
  gbuffer.bind(round_);
  round_.set("params", params)
      .set_buffer<cl_uint>("pixel_list", pixel_list_)
      .set("item_count", cl_uint(item_count))
      .set_buffer<cl_float4>("direct_out", radiance_)
      .set_buffer<cl_float4>("direct_sums", sums_)
      .set_buffer<cl_float4>("direct_moments", moments_)
      .launch(item_count * size_t(gbuffer.sub_pixel_side * gbuffer.sub_pixel_side), gpu_.groups().traversal);
}

DirectRunStats DirectPass::run_rounds(const GBufferView& gbuffer, unsigned seed, unsigned light_budget) {
  const size_t bytes = std::max<size_t>(pixels_, 1) * sizeof(cl_float4);
  if (!sums_()) {
    sums_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "direct light sums");
    moments_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "direct light moments");
  }
  if (!pixel_list_()) pixel_list_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_ONLY, "direct pixel list");
  const size_t output_pixels = gbuffer.output_pixel_count();
  const unsigned sub_pixels = unsigned(gbuffer.sub_pixel_side * gbuffer.sub_pixel_side);
  DirectParams params{};
  params.seed = seed;
  // One sample a sub-pixel first (four an output pixel at 2 x 2), four where the pixel is its own sub-pixel: a
  // variance needs two.
  const unsigned first_samples = std::max(1u, 4u / sub_pixels);
  params.first_sample = 0;
  params.round_samples = first_samples;
  params.listed = 0;
  run_round(gbuffer, params, output_pixels);
  gpu_.reserve<cl_float4>(pixel_errors_, errors_capacity_, std::max<size_t>(output_pixels, 1), "direct pixel errors");
  gbuffer.bind(pixel_error_);
  pixel_error_.set_buffer<cl_float4>("direct_out", radiance_)
      .set_buffer<cl_float4>("direct_sums", sums_)
      .set_buffer<cl_float4>("direct_moments", moments_)
      .set("output_pixels", cl_uint(output_pixels))
      .set_buffer<cl_float4>("error_out", pixel_errors_)
      .launch(output_pixels, gpu_.groups().per_item);
  // The budget per output pixel, split among its sub-pixels, in chunks of the first round's samples.
  const int side = gbuffer.sub_pixel_side;
  const RoundsPlan plan = plan_rounds(gpu_.download<cl_float4>(pixel_errors_, output_pixels), gbuffer.width / side,
                                      gbuffer.height / side,
                                      double(light_budget) / double(sub_pixels * first_samples));
  DirectRunStats stats;
  stats.sampled_sub_pixels = plan.sampled_sub_pixels;
  stats.samples = plan.chunks * first_samples;
  stats.refined_pixels = plan.refined_pixels;
  stats.rounds = run_later_rounds(plan.levels, [&](const std::vector<cl_uint>& listed, unsigned first, unsigned count) {
    gpu_.upload_into(pixel_list_, list_capacity_, listed, CL_MEM_READ_ONLY, "direct pixel list");
    params.first_sample = first * first_samples;
    params.round_samples = count * first_samples;
    params.listed = 1;
    run_round(gbuffer, params, listed.size());
  });
  average_.set_buffer<cl_float4>("direct_sums", sums_)
      .set_buffer<cl_float4>("direct_moments", moments_)
      .set("pixel_count", cl_uint(pixels_))
      .set_buffer<cl_float4>("direct_out", radiance_)
      .launch(pixels_, gpu_.groups().per_item);
  gpu_.queue().finish();
  return stats;
}

}  // namespace rcsplat
