#include "passes/gbuffer_pass.h"

#include <algorithm>

namespace rcsplat {
void GBufferPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) { gpu.build_ahead(kProgram, scene.defines()); }

void GBufferView::bind(NamedKernel& kernel) const {
  kernel.set_buffer<GBufferSample>("gbuffer", samples).set_buffer<CameraParams>("camera", camera);
}

GBufferPass::GBufferPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "gbuffer", scene.defines())) {}

void GBufferPass::run(const CameraParams& camera) {
  size_t pixels = size_t(camera.width) * size_t(camera.height);
  if (pixels != view_.pixel_count() || !view_.samples())
    view_.samples = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(pixels, 1) * sizeof(GBufferSample), "G-buffer");
  view_.width = camera.width;
  view_.height = camera.height;
  view_.sub_pixel_side = std::max(camera.sub_pixel_side, 1);
  gpu_.upload_into(view_.camera, camera_capacity_, std::vector<CameraParams>{camera}, CL_MEM_READ_ONLY, "G-buffer");
  scene_.bind(kernel_);
  view_.bind(kernel_);
  // Square tiles: neighbouring rays in one group, as the traversal prefers.
  kernel_.launch_2d(size_t(camera.width), size_t(camera.height), gpu_.groups().tile_side);
  gpu_.queue().finish();
}

std::vector<GBufferSample> GBufferPass::download() {
  return gpu_.download<GBufferSample>(view_.samples, view_.pixel_count());
}

}  // namespace rcsplat
