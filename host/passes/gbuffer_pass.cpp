#include "passes/gbuffer_pass.h"

#include <algorithm>

namespace rcsplat {
void GBufferPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) { gpu.build_ahead(kProgram, scene.defines()); }

void GBufferView::bind(NamedKernel& kernel) const {
  kernel.set_buffer<GBufferSample>("gbuffer", samples)
      .set_buffer<CameraParams>("camera", camera)
      .set_buffer<SurfaceLayers>("gbuffer_layers", layers);
}

void GBufferView::bind_see_through(NamedKernel& kernel) const { kernel.set_buffer<cl_float4>("see_through", see_through); }

GBufferPass::GBufferPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "gbuffer", scene.defines())) {
  if (scene.has_glass()) weigh_ = gpu.kernel(kProgram, "weigh_through_glass", scene.defines());
}

void GBufferPass::run(const CameraParams& camera) {
  size_t pixels = size_t(camera.width) * size_t(camera.height);
  if (pixels != view_.pixel_count() || !view_.samples()) {
    view_.samples = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(pixels, 1) * sizeof(GBufferSample), "G-buffer");
    const size_t weights = scene_.has_glass() ? std::max<size_t>(pixels, 1) : 1;
    view_.see_through = gpu_.buffer(CL_MEM_READ_WRITE, weights * sizeof(cl_float4), "G-buffer");
    view_.glass_mirrors = gpu_.buffer(CL_MEM_READ_WRITE, 2 * weights * sizeof(cl_float4), "G-buffer");
    const size_t layered = scene_.has_layers() ? std::max<size_t>(pixels, 1) : 1;
    view_.layers = gpu_.buffer(CL_MEM_READ_WRITE, layered * sizeof(SurfaceLayers), "G-buffer");
  }
  view_.width = camera.width;
  view_.height = camera.height;
  view_.sub_pixel_side = std::max(camera.sub_pixel_side, 1);
  gpu_.upload_into(view_.camera, camera_capacity_, std::vector<CameraParams>{camera}, CL_MEM_READ_ONLY, "G-buffer");
  scene_.bind(kernel_);
  view_.bind(kernel_);
  view_.bind_see_through(kernel_);
  kernel_.set_buffer<cl_float4>("glass_mirrors", view_.glass_mirrors);
  // Square tiles: neighbouring rays in one group, as the traversal prefers.
  kernel_.launch_2d(size_t(camera.width), size_t(camera.height), gpu_.groups().tile_side);
  gpu_.queue().finish();
}

void GBufferPass::weigh_through_glass(const cl::Buffer& light) {
  if (!scene_.has_glass()) return;
  weigh_.set_buffer<cl_float4>("see_through", view_.see_through)
      .set("pixel_count", cl_uint(view_.pixel_count()))
      .set_buffer<cl_float4>("light", light);
  weigh_.launch(view_.pixel_count(), gpu_.groups().per_item);
  gpu_.queue().finish();
}

std::vector<GBufferSample> GBufferPass::download() {
  return gpu_.download<GBufferSample>(view_.samples, view_.pixel_count());
}

}  // namespace rcsplat
