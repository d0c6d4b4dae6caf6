// Record computation (kernels/records.cl): owns the record array, which grows as placement adds batches.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/device_scene.h"

namespace rcsplat {

class RecordPass {
 public:
  RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata);

  // Computes records first .. first + count - 1 from the G-buffer samples (GBufferSample) listed in candidates, with
  // radius clamps in pixels of the camera (CameraParams); blocks until done.
  void compute(const cl::Buffer& gbuffer, const cl::Buffer& camera, const cl::Buffer& candidates, uint32_t count,
               uint32_t first, const HemisphereParams& params);
  cl::Buffer& records() { return records_; }
  uint64_t rays_cast();  // hemisphere and shadow rays cast so far
  std::vector<CacheRecord> download(size_t count);

  static constexpr unsigned kMaxThetaStrata = 64;  // the largest M offered

 private:
  void reserve(size_t count);  // grows the array, keeping what it holds

  GpuContext& gpu_;
  const DeviceScene& scene_;
  cl::Kernel kernel_;
  cl::Buffer records_, ray_total_;
  size_t capacity_ = 0;
};

}  // namespace rcsplat
