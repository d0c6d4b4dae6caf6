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
  ComposePass(GpuContext& gpu, const DeviceScene& scene);
  // irradiance: float4 per pixel (E.rgb, weight; 0 where uncovered); direct: DirectPass's RGBA; glossy: GlossyPass's
  // RGBA, or nullptr where the scene has no glossy pixel. Blocks until done.
  void run(const GBufferView& gbuffer, const cl::Buffer& irradiance, const cl::Buffer& direct, const cl::Buffer* glossy);

  std::vector<float> indirect_rgba();  // A = 1 where a record reached the pixel
  std::vector<float> color_rgba();

 private:
  GpuContext& gpu_;
  NamedKernel kernel_;
  cl::Buffer indirect_, color_, specular_albedo_table_;  // the rough lobes' albedo (kernels/brdf_frame.h)
  size_t pixels_ = 0;
};

}  // namespace rcsplat
