// Casts arbitrary batches of rays through the device BVH (kernels/ray_cast.cl): the traversal's test and benchmark
// entry point.
#pragma once
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/device_bvh.h"

namespace rcsplat {

class RayCastPass {
 public:
  RayCastPass(GpuContext& gpu, const DeviceBvh& bvh);

  // Uploads rays once so that repeated casts (benchmarks) time the kernel alone.
  void set_rays(const std::vector<RayDesc>& rays);
  // Runs the kernel on the uploaded rays and waits; returns the wall-clock seconds of the launch.
  double cast_closest();
  double cast_occlusion();
  std::vector<HitDesc> closest_hits();
  std::vector<int> occlusion();

 private:
  double cast(cl::Kernel& kernel, const cl::Buffer& results);  // binds the arguments shared by both kernels
  double run(cl::Kernel& kernel);

  GpuContext& gpu_;
  const DeviceBvh& bvh_;
  cl::Kernel closest_, occlusion_;
  cl::Buffer rays_, hits_, occluded_;
  size_t ray_count_ = 0;
};

// The work-group size the traversal kernels run with: PoCL runs 15% slower when it picks one itself.
constexpr size_t kTraversalLocalSize = 64;

inline size_t round_up(size_t n, size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

}  // namespace rcsplat
