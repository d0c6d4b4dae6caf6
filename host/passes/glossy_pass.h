// The specular indirect light of glossy pixels (kernels/glossy.cl), sampled from each pixel's own lobe; the cache
// carries the rest. Compiled and run only for scenes with a glossy material (DeviceScene's HAS_SPECULAR_BRDF).
#pragma once
#include <cstdint>
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class GlossyPass {
 public:
  // sample_radiance_cacheable: also sample the LOBE_HSH pixels (cache methods without radiance caching: the octree).
  GlossyPass(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable);
  // samples per glossy pixel, stratified over a grid of floor(sqrt(samples))^2; with a light guide's clusters, half
  // as many again aimed at those a pixel's lobe faces (kernels/glossy.cl). With radiance records that left the
  // guide's share to the pixels (record_guide_rays guided rays beside record_strata strata, both > 0), the
  // radiance-cached pixels get that share from as many samples. Blocks until done.
  void run(const GBufferView& gbuffer, unsigned samples, unsigned seed, const std::vector<GuideCluster>& guide = {},
           unsigned record_strata = 0, unsigned record_guide_rays = 0, unsigned bounces = 1);
  const cl::Buffer& radiance() const { return radiance_; }  // float4 per pixel: RGB, A = rays cast
  std::vector<float> download_rgba();

 private:
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
  cl::Buffer radiance_, guide_;
  size_t pixels_ = 0, guide_capacity_ = 0;
};

}  // namespace rcsplat
