// Primary visibility (kernels/gbuffer.cl): owns the G-buffer.
#pragma once
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/device_scene.h"

namespace rcsplat {

class GBufferPass {
 public:
  GBufferPass(GpuContext& gpu, const DeviceScene& scene);
  void run(const CameraParams& camera);  // blocks until done
  const cl::Buffer& samples() const { return samples_; }
  const cl::Buffer& camera() const { return camera_; }  // the CameraParams of the last run
  std::vector<GBufferSample> download();
  size_t pixel_count() const { return pixels_; }

 private:
  GpuContext& gpu_;
  const DeviceScene& scene_;
  cl::Kernel kernel_;
  cl::Buffer camera_, samples_;
  size_t pixels_ = 0;
};

}  // namespace rcsplat
