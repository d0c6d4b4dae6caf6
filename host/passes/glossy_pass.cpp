#include "passes/glossy_pass.h"

#include <cmath>

namespace rcsplat {

GlossyPass::GlossyPass(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable)
    : gpu_(gpu),
      scene_(scene),
      kernel_(gpu.kernel("glossy.cl", "glossy_indirect", scene.defines_with("SAMPLE_HSH_LOBES", sample_radiance_cacheable))) {}

void GlossyPass::run(const GBufferView& gbuffer, unsigned samples, unsigned seed) {
  if (gbuffer.pixel_count() != pixels_ || !radiance_()) {
    pixels_ = gbuffer.pixel_count();
    radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(pixels_, 1) * 4 * sizeof(float), "glossy radiance");
  }
  PathParams params{};
  params.sample_count = samples;
  params.grid_side = unsigned(std::sqrt(double(samples)));
  params.seed = seed;
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set("params", params).set_buffer<cl_float4>("glossy_out", radiance_);
  kernel_.launch(pixels_, gpu_.groups().traversal);
  gpu_.queue().finish();
}

std::vector<float> GlossyPass::download_rgba() { return gpu_.download<float>(radiance_, pixels_ * 4); }

}  // namespace rcsplat
