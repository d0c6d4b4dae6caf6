#include "passes/direct_pass.h"

namespace rcsplat {
void DirectPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) { gpu.build_ahead(kProgram, scene.defines()); }

DirectPass::DirectPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "direct_light", scene.defines())) {}

void DirectPass::run(const GBufferView& gbuffer, unsigned strata_per_axis, unsigned seed) {
  if (gbuffer.pixel_count() != pixels_ || !radiance_()) {
    pixels_ = gbuffer.pixel_count();
    radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(pixels_, 1) * 4 * sizeof(float), "direct radiance");
  }
  DirectParams params{};
  params.strata_per_axis = strata_per_axis;
  params.seed = seed;
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set("params", params).set_buffer<cl_float4>("direct_out", radiance_);
  kernel_.launch(pixels_, gpu_.groups().traversal);
  gpu_.queue().finish();
}

}  // namespace rcsplat
