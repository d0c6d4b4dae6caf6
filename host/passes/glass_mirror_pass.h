// Lit surfaces camera rays see mirrored in glass (kernels/glass_mirror.cl), added to the pixels' direct light: scenes
// with glass only.
#pragma once
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class GlassMirrorPass {
 public:
  GlassMirrorPass(GpuContext& gpu, const DeviceScene& scene);
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);
  // Adds to direct (float4 a pixel: RGB, A shadow rays) what each pixel sees mirrored in the glass its camera ray met
  // first, from `samples` paths of `bounces` indirect bounces after the mirrored surface's direct light (0: its direct
  // light alone, for frames of direct light). Blocks.
  void run(const GBufferView& gbuffer, const cl::Buffer& direct, unsigned samples, unsigned seed, unsigned bounces);

 private:
  static constexpr const char* kProgram = "glass_mirror.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
};

}  // namespace rcsplat
