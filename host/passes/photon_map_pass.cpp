#include "passes/photon_map_pass.h"

#include "cl/point_lookup.h"
#include "passes/light_guide_pass.h"

namespace rcsplat {
namespace {
constexpr const char* kProgram = "photon_map.cl";
}  // namespace

void PhotonMapPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }

std::vector<PhotonHit> shoot_reflected_photons(GpuContext& gpu, const DeviceScene& scene, unsigned paths,
                                               unsigned bounces, unsigned seed) {
  return lit_landings(LightGuidePass(gpu, scene).shoot(paths, seed, bounces, 1));
}

PhotonMapPass::PhotonMapPass(GpuContext& gpu, const PhotonMapGrids& grids) : gpu_(gpu), params_(grids.lookup.params) {
  photons_ = gpu.upload(grids.lookup.photons, CL_MEM_READ_ONLY, "photon map");
  buckets_ = gpu.upload(grids.lookup.bucket_starts, CL_MEM_READ_ONLY, "photon map buckets");
  // Two float4 per lookup photon: the reflected light and the irradiance (kernels/photon_map.h).
  const size_t estimate_bytes = std::max<size_t>(grids.lookup.photons.size(), 1) * 2 * sizeof(cl_float4);
  radiance_ = gpu.buffer(CL_MEM_READ_WRITE, estimate_bytes, "photon map estimates");
  shallow_ = gpu.buffer(CL_MEM_READ_WRITE, estimate_bytes, "photon map shallow estimates");
  if (grids.lookup.photons.empty()) return;
  cl::Buffer all_photons = gpu.upload(grids.all.photons, CL_MEM_READ_ONLY, "photon map");
  cl::Buffer all_buckets = gpu.upload(grids.all.bucket_starts, CL_MEM_READ_ONLY, "photon map buckets");
  // The kernel reads no patch when there are none, but a buffer must be bound.
  cl::Buffer patches = gpu.upload(grids.patches.patches.empty() ? std::vector<SurfacePatch>(1) : grids.patches.patches,
                                  CL_MEM_READ_ONLY, "photon map surface patches");
  cl::Buffer patch_buckets = gpu.upload(grids.patches.bucket_starts.empty() ? std::vector<cl_uint>(2, 0u)
                                                                           : grids.patches.bucket_starts,
                                        CL_MEM_READ_ONLY, "photon map surface patch buckets");
  cl::Buffer order = gpu.upload(cell_order(grids.lookup), CL_MEM_READ_ONLY, "photon map estimate order");
  NamedKernel estimate = gpu.kernel(kProgram, "estimate_photon_radiance", {});
  estimate.set_buffer<PhotonHit>("all_photons", all_photons)
      .set_buffer<cl_uint>("all_buckets", all_buckets)
      .set("all_grid", grids.all.params)
      .set_buffer<SurfacePatch>("patches", patches)
      .set_buffer<cl_uint>("patch_buckets", patch_buckets)
      .set("patch_grid", grids.patches.params)
      .set_buffer<PhotonHit>("map_photons", photons_)
      .set("map", params_)
      .set("shallow_landings", cl_int(grids.shallow_landings))
      .set_buffer<cl_float4>("map_radiance", radiance_)
      .set_buffer<cl_float4>("map_shallow", shallow_)
      .set_buffer<cl_uint>("estimate_order", order);
  estimate.launch(params_.photon_count, gpu.groups().traversal);
  gpu.queue().finish();
}

void PhotonMapPass::set_lookup(float short_ray_paths, float min_support) {
  params_.short_path_distance = short_ray_paths * params_.radius;
  params_.min_support = min_support;
}

void PhotonMapPass::bind(NamedKernel& kernel) const {
  kernel.set_buffer<PhotonHit>("map_photons", photons_)
      .set_buffer<cl_float4>("map_radiance", radiance_)
      .set_buffer<cl_float4>("map_shallow", shallow_)
      .set_buffer<cl_uint>("map_buckets", buckets_)
      .set("map", params_);
}

std::vector<cl_float4> PhotonMapPass::estimates() {
  return gpu_.download<cl_float4>(radiance_, 2 * size_t(params_.photon_count));
}

std::vector<cl_float4> PhotonMapPass::shallow_estimates() {
  return gpu_.download<cl_float4>(shallow_, 2 * size_t(params_.photon_count));
}

std::vector<cl_float4> PhotonMapPass::radiance_at(const std::vector<cl_float4>& points,
                                                  const std::vector<cl_float4>& normals) {
  NamedKernel look_up = gpu_.kernel(kProgram, "look_up_photon_radiance", {});
  bind(look_up);
  return run_point_lookup(gpu_, look_up, points, normals, "radiance");
}

}  // namespace rcsplat
