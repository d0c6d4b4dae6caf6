// Composition (kernels/compose.cl), shared by every cache method: the pixels' indirect light from the cached
// irradiance, each by its own BRDF, and the final colour. Owns the composed images.
#pragma once
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class ComposePass {
 public:
  // radiance_cached: the LOBE_HSH pixels' lobes come from the radiance cache, not from GlossyPass.
  ComposePass(GpuContext& gpu, const DeviceScene& scene, bool radiance_cached);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene, bool radiance_cached);
  // irradiance: float4 per pixel (E.rgb, weight; 0 where uncovered); direct: DirectPass's RGBA; glossy: GlossyPass's
  // RGBA, or nullptr where no pixel is sampled; cached_lobes: RadianceSplatPass's lobe radiance, or nullptr without
  // radiance caching; glossy_holds_guide_share: glossy also holds the radiance-cached pixels' light-guide share
  // (kernels/glossy.cl guide_share), added to their cached lobes. Blocks until done.
  void run(const GBufferView& gbuffer, const cl::Buffer& irradiance, const cl::Buffer& direct, const cl::Buffer* glossy,
           const cl::Buffer* cached_lobes, bool glossy_holds_guide_share = false);

  const cl::Buffer& indirect() const { return indirect_; }  // float4: RGB, A = 1 where a record reached the pixel
  const cl::Buffer& color() const { return color_; }        // float4: emission + direct + indirect, A = 1

 private:
  static constexpr const char* kProgram = "compose.cl";  // its kernels' file
  GpuContext& gpu_;
  NamedKernel kernel_;
  cl::Buffer indirect_, color_;
  size_t pixels_ = 0;
};

}  // namespace rcsplat
