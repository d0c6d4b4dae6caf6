#include "passes/ray_cast_pass.h"

#include <chrono>

namespace rcsplat {

RayCastPass::RayCastPass(GpuContext& gpu, const DeviceBvh& bvh) : gpu_(gpu), bvh_(bvh) {
  KernelDefines defines;
  bvh_.add_defines(defines);
  cl::Program& program = gpu_.program("ray_cast.cl", defines);
  closest_ = cl::Kernel(program, "cast_closest");
  occlusion_ = cl::Kernel(program, "cast_occlusion");
}

void RayCastPass::set_rays(const std::vector<RayDesc>& rays) {
  ray_count_ = rays.size();
  rays_ = gpu_.upload(rays);
  hits_ = cl::Buffer(gpu_.context(), CL_MEM_WRITE_ONLY, std::max<size_t>(ray_count_, 1) * sizeof(HitDesc));
  occluded_ = cl::Buffer(gpu_.context(), CL_MEM_WRITE_ONLY, std::max<size_t>(ray_count_, 1) * sizeof(int));
}

double RayCastPass::run(cl::Kernel& kernel) {
  if (ray_count_ == 0) return 0.0;
  auto start = std::chrono::steady_clock::now();
  gpu_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(round_up(ray_count_, kTraversalLocalSize)),
                                    cl::NDRange(kTraversalLocalSize));
  gpu_.queue().finish();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double RayCastPass::cast(cl::Kernel& kernel, const cl::Buffer& results) {
  kernel.setArg(0, bvh_.nodes());
  kernel.setArg(1, bvh_.blocks());
  kernel.setArg(2, rays_);
  kernel.setArg(3, results);
  kernel.setArg(4, cl_uint(ray_count_));
  return run(kernel);
}

double RayCastPass::cast_closest() { return cast(closest_, hits_); }
double RayCastPass::cast_occlusion() { return cast(occlusion_, occluded_); }

std::vector<HitDesc> RayCastPass::closest_hits() { return gpu_.download<HitDesc>(hits_, ray_count_); }
std::vector<int> RayCastPass::occlusion() { return gpu_.download<int>(occluded_, ray_count_); }

}  // namespace rcsplat
