#include "passes/gbuffer_pass.h"

#include "passes/ray_cast_pass.h"

namespace rcsplat {

GBufferPass::GBufferPass(GpuContext& gpu, const DeviceScene& scene) : gpu_(gpu), scene_(scene) {
  kernel_ = cl::Kernel(gpu_.program("gbuffer.cl", scene_.defines()), "gbuffer");
}

void GBufferPass::run(const CameraParams& camera) {
  size_t pixels = size_t(camera.width) * size_t(camera.height);
  if (pixels != pixels_) {
    samples_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, pixels * sizeof(GBufferSample));
    pixels_ = pixels;
  }
  camera_ = gpu_.upload(std::vector<CameraParams>{camera});
  int a = 0;
  for (const cl::Buffer* b : std::initializer_list<const cl::Buffer*>{&scene_.bvh().nodes(), &scene_.bvh().blocks(), &scene_.triangles(), &scene_.materials(),
                              &scene_.textures(), &scene_.texels(), &camera_, &samples_})
    kernel_.setArg(cl_uint(a++), *b);
  // 8 x 8 tiles: 64 work-items, as the traversal prefers, and neighbouring rays in one group.
  gpu_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange,
                                    cl::NDRange(round_up(size_t(camera.width), 8), round_up(size_t(camera.height), 8)),
                                    cl::NDRange(8, 8));
  gpu_.queue().finish();
}

std::vector<GBufferSample> GBufferPass::download() { return gpu_.download<GBufferSample>(samples_, pixels_); }

}  // namespace rcsplat
