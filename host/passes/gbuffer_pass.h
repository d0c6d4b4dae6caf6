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
  // Per pixel, what the glass its camera ray looked through kept (RGB; kernels/gbuffer.cl): the pixel's direct and
  // indirect light are weighed by it. One unread float4 in a scene without glass.
  cl::Buffer see_through;
  // Per pixel two float4: the ray its camera ray's first glass point mirrors (origin and R, direction), for
  // kernels/glass_mirror.cl; one unread pair without glass.
  cl::Buffer glass_mirrors;
  // Per pixel its surface's layers (SurfaceLayers: clearcoat, sheen, specular colour; kernels/brdf_layers.h) in a
  // scene with them; one unread element otherwise.
  cl::Buffer layers;

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  size_t output_pixel_count() const { return pixel_count() / size_t(sub_pixel_side * sub_pixel_side); }
  // Sets a kernel's GBUFFER_ARGS ("gbuffer", "camera" and "gbuffer_layers").
  void bind(NamedKernel& kernel) const;
  // Sets a kernel's "see_through".
  void bind_see_through(NamedKernel& kernel) const;
};

class GBufferPass {
 public:
  GBufferPass(GpuContext& gpu, const DeviceScene& scene);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);
  void run(const CameraParams& camera);  // blocks until done
  const GBufferView& view() const { return view_; }
  std::vector<GBufferSample> download();
  // Weighs per-pixel light (RGB of a float4 a pixel) by what the glass its camera ray looked through kept; nothing to
  // do in a scene without glass.
  void weigh_through_glass(const cl::Buffer& light);

 private:
  static constexpr const char* kProgram = "gbuffer.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
  NamedKernel weigh_;  // weigh_through_glass, in scenes with glass
  GBufferView view_;
  size_t camera_capacity_ = 0;
};

}  // namespace rcsplat
