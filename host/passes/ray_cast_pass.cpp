#include "passes/ray_cast_pass.h"

#include <chrono>

namespace rcsplat {
namespace {

double timed(GpuContext& gpu, NamedKernel& kernel, const DeviceScene& scene, const cl::Buffer& rays, size_t count,
             const char* result_name, const cl::Buffer& results, bool hits) {
  if (count == 0) return 0.0;
  RayCastParams params{};
  params.ray_count = cl_uint(count);
  scene.bind(kernel);
  kernel.set_buffer<RayDesc>("rays", rays).set("params", params);
  if (hits) kernel.set_buffer<HitDesc>(result_name, results);
  else kernel.set_buffer<cl_int>(result_name, results);
  auto start = std::chrono::steady_clock::now();
  kernel.launch(count, gpu.groups().traversal);
  gpu.queue().finish();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

RayCastPass::RayCastPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu),
      scene_(scene),
      closest_(gpu.kernel("ray_cast.cl", "cast_closest", scene.defines())),
      occlusion_(gpu.kernel("ray_cast.cl", "cast_occlusion", scene.defines())) {}

void RayCastPass::set_rays(const std::vector<RayDesc>& rays) {
  ray_count_ = rays.size();
  rays_ = gpu_.upload(rays, CL_MEM_READ_ONLY, "rays");
  hits_ = gpu_.buffer(CL_MEM_WRITE_ONLY, std::max<size_t>(ray_count_, 1) * sizeof(HitDesc), "ray cast hits");
  occluded_ = gpu_.buffer(CL_MEM_WRITE_ONLY, std::max<size_t>(ray_count_, 1) * sizeof(int), "ray cast occluded");
}

double RayCastPass::cast_closest() { return timed(gpu_, closest_, scene_, rays_, ray_count_, "hits", hits_, true); }
double RayCastPass::cast_occlusion() {
  return timed(gpu_, occlusion_, scene_, rays_, ray_count_, "occluded", occluded_, false);
}

std::vector<HitDesc> RayCastPass::closest_hits() { return gpu_.download<HitDesc>(hits_, ray_count_); }
std::vector<int> RayCastPass::occlusion() { return gpu_.download<int>(occluded_, ray_count_); }

}  // namespace rcsplat
