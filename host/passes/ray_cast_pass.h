// Casts arbitrary batches of rays through the device BVH (kernels/ray_cast.cl): the traversal's test and benchmark
// entry point.
#pragma once
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"

namespace rcsplat {

class RayCastPass {
 public:
  RayCastPass(GpuContext& gpu, const DeviceScene& scene);

  // Uploads rays once so that repeated casts (benchmarks) time the kernel alone.
  void set_rays(const std::vector<RayDesc>& rays);
  // Runs the kernel on the uploaded rays and waits; returns the wall-clock seconds of the launch.
  double cast_closest();
  double cast_occlusion();
  std::vector<HitDesc> closest_hits();
  std::vector<int> occlusion();

 private:
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel closest_, occlusion_;
  cl::Buffer rays_, hits_, occluded_;
  size_t ray_count_ = 0;
};

}  // namespace rcsplat
