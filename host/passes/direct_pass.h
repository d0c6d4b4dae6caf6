// Direct light (kernels/direct.cl): owns the direct-radiance image.
#pragma once
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class DirectPass {
 public:
  DirectPass(GpuContext& gpu, const DeviceScene& scene);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);
  // strata_per_axis^2 stratified samples on the emissive triangles per pixel; seed varies the sample pattern.
  void run(const GBufferView& gbuffer, unsigned strata_per_axis, unsigned seed);
  // float4 per pixel: reflected direct radiance RGB, A = shadow rays the pixel cast.
  const cl::Buffer& radiance() const { return radiance_; }

 private:
  static constexpr const char* kProgram = "direct.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
  cl::Buffer radiance_;
  size_t pixels_ = 0;
};

}  // namespace rcsplat
