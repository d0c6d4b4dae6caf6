#include "passes/direct_pass.h"

#include "passes/ray_cast_pass.h"

namespace rcsplat {

DirectPass::DirectPass(GpuContext& gpu, const DeviceScene& scene) : gpu_(gpu), scene_(scene) {
  kernel_ = cl::Kernel(gpu_.program("direct.cl", scene_.defines()), "direct_light");
}

void DirectPass::run(const GBufferPass& gbuffer, unsigned strata_per_axis, unsigned seed) {
  if (gbuffer.pixel_count() != pixels_) {
    pixels_ = gbuffer.pixel_count();
    radiance_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, std::max<size_t>(pixels_, 1) * 4 * sizeof(float));
  }
  kernel_.setArg(0, scene_.bvh().nodes());
  kernel_.setArg(1, scene_.bvh().blocks());
  kernel_.setArg(2, gbuffer.samples());
  kernel_.setArg(3, scene_.lights());
  kernel_.setArg(4, scene_.light_count());
  kernel_.setArg(5, scene_.emitters());
  kernel_.setArg(6, scene_.emitter_count());
  kernel_.setArg(7, cl_uint(strata_per_axis));
  kernel_.setArg(8, cl_uint(seed));
  kernel_.setArg(9, cl_uint(pixels_));
  kernel_.setArg(10, radiance_);
  gpu_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(round_up(pixels_, kTraversalLocalSize)),
                                    cl::NDRange(kTraversalLocalSize));
  gpu_.queue().finish();
}

std::vector<float> DirectPass::download_rgba() { return gpu_.download<float>(radiance_, pixels_ * 4); }

}  // namespace rcsplat
