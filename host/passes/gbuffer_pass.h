// Primary visibility (kernels/gbuffer.cl): owns the G-buffer and its camera, which every later pass reads through a
// GBufferView.
#pragma once
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"

namespace rcsplat {

// The G-buffer and its camera, as every pass receives them (kernels/scene_args.h GBUFFER_ARGS).
struct GBufferView {
  cl::Buffer samples;  // GBufferSample per pixel, row-major from the top
  cl::Buffer camera;   // one CameraParams
  int width = 0, height = 0;
  int sub_pixel_side = 1;  // the frame's output pixels are sub_pixel_side^2 of these (CameraParams::sub_pixel_side)

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  size_t output_pixel_count() const { return pixel_count() / size_t(sub_pixel_side * sub_pixel_side); }
  // Sets a kernel's GBUFFER_ARGS ("gbuffer" and "camera").
  void bind(NamedKernel& kernel) const;
};

class GBufferPass {
 public:
  GBufferPass(GpuContext& gpu, const DeviceScene& scene);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);
  void run(const CameraParams& camera);  // blocks until done
  const GBufferView& view() const { return view_; }
  std::vector<GBufferSample> download();

 private:
  static constexpr const char* kProgram = "gbuffer.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
  GBufferView view_;
  size_t camera_capacity_ = 0;
};

}  // namespace rcsplat
