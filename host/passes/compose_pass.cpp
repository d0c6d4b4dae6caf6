#include "passes/compose_pass.h"

namespace rcsplat {
void ComposePass::build_ahead(GpuContext& gpu, const DeviceScene& scene, bool radiance_cached) { gpu.build_ahead(kProgram, scene.defines_with("RADIANCE_CACHED", radiance_cached)); }

ComposePass::ComposePass(GpuContext& gpu, const DeviceScene& scene, bool radiance_cached)
    : gpu_(gpu),
      kernel_(gpu.kernel(kProgram, "compose", scene.defines_with("RADIANCE_CACHED", radiance_cached))) {}

void ComposePass::run(const GBufferView& gbuffer, const cl::Buffer& irradiance, const cl::Buffer& direct,
                      const cl::Buffer* glossy, const cl::Buffer* cached_lobes, bool glossy_holds_guide_share) {
  if (gbuffer.pixel_count() != pixels_ || !indirect_()) {
    pixels_ = gbuffer.pixel_count();
    size_t bytes = std::max<size_t>(pixels_, 1) * 4 * sizeof(float);
    indirect_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "compose indirect");
    color_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "compose color");
  }
  gbuffer.bind(kernel_);
  // Without glossy (radiance-cached) pixels the kernel never reads "glossy" ("cached_lobes"): any float4 buffer of
  // the frame's size stands in.
  kernel_.set_buffer<cl_float4>("irradiance", irradiance)
      .set_buffer<cl_float4>("direct", direct)
      .set_buffer<cl_float4>("glossy", glossy ? *glossy : irradiance)
      .set_buffer<cl_float4>("cached_lobes", cached_lobes ? *cached_lobes : irradiance)
      .set("glossy_holds_guide_share", cl_uint(glossy && glossy_holds_guide_share))
      .set_buffer<cl_float4>("see_through", gbuffer.see_through)
      .set_buffer<cl_float4>("indirect_out", indirect_)
      .set_buffer<cl_float4>("color_out", color_);
  kernel_.launch(pixels_, gpu_.groups().per_item);
  gpu_.queue().finish();
}

}  // namespace rcsplat
