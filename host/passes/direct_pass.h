// Direct light (kernels/direct.cl): owns the direct-radiance image.
#pragma once
#include "cl/gpu_context.h"
#include "passes/device_scene.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class DirectPass {
 public:
  DirectPass(GpuContext& gpu, const DeviceScene& scene);
  // strata_per_axis^2 stratified samples on the emissive triangles per pixel; seed varies the sample pattern.
  void run(const GBufferPass& gbuffer, unsigned strata_per_axis, unsigned seed);
  std::vector<float> download_rgba();  // reflected direct radiance, RGBA (A = 1)
  const cl::Buffer& radiance() const { return radiance_; }

 private:
  GpuContext& gpu_;
  const DeviceScene& scene_;
  cl::Kernel kernel_;
  cl::Buffer radiance_;
  size_t pixels_ = 0;
};

}  // namespace rcsplat
