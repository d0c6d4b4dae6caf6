#include "passes/glass_mirror_pass.h"

#include <algorithm>

namespace rcsplat {

void GlassMirrorPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) {
  gpu.build_ahead(kProgram, scene.defines());
}

GlassMirrorPass::GlassMirrorPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "mirror_in_glass", scene.defines())) {}

void GlassMirrorPass::run(const GBufferView& gbuffer, const cl::Buffer& direct, unsigned samples, unsigned seed,
                          unsigned bounces) {
  GlassMirrorParams params{};
  params.pixel_count = cl_uint(gbuffer.pixel_count());
  params.samples = std::max(samples, 1u);
  params.seed = seed;
  params.bounces = bounces;
  scene_.bind(kernel_);
  kernel_.set_buffer<cl_float4>("mirrors", gbuffer.glass_mirrors)
      .set("params", params)
      .set_buffer<cl_float4>("direct_out", direct);
  kernel_.launch(gbuffer.pixel_count(), gpu_.groups().traversal);
  gpu_.queue().finish();
}

}  // namespace rcsplat
