#include "passes/photon_map_pass.h"

#include "passes/light_guide_pass.h"

namespace rcsplat {

std::vector<PhotonHit> shoot_reflected_photons(GpuContext& gpu, const DeviceScene& scene, unsigned paths,
                                               unsigned bounces, unsigned seed) {
  return lit_landings(LightGuidePass(gpu, scene).shoot(paths, seed, bounces, 1));
}

PhotonMapPass::PhotonMapPass(GpuContext& gpu, const PhotonMapGrids& grids) : gpu_(gpu), params_(grids.lookup.params) {
  photons_ = gpu.upload(grids.lookup.photons, CL_MEM_READ_ONLY, "photon map");
  buckets_ = gpu.upload(grids.lookup.bucket_starts, CL_MEM_READ_ONLY, "photon map buckets");
  radiance_ = gpu.buffer(CL_MEM_READ_WRITE, std::max<size_t>(grids.lookup.photons.size(), 1) * sizeof(cl_float4),
                         "photon map radiance");
  shallow_ = gpu.buffer(CL_MEM_READ_WRITE, std::max<size_t>(grids.lookup.photons.size(), 1) * sizeof(cl_float4),
                        "photon map shallow radiance");
  if (grids.lookup.photons.empty()) return;
  cl::Buffer all_photons = gpu.upload(grids.all.photons, CL_MEM_READ_ONLY, "photon map");
  cl::Buffer all_buckets = gpu.upload(grids.all.bucket_starts, CL_MEM_READ_ONLY, "photon map buckets");
  NamedKernel estimate = gpu.kernel("photon_map.cl", "estimate_photon_radiance", {});
  estimate.set_buffer<PhotonHit>("all_photons", all_photons)
      .set_buffer<cl_uint>("all_buckets", all_buckets)
      .set("all_grid", grids.all.params)
      .set_buffer<PhotonHit>("map_photons", photons_)
      .set("map", params_)
      .set("shallow_landings", cl_int(grids.shallow_landings))
      .set_buffer<cl_float4>("map_radiance", radiance_)
      .set_buffer<cl_float4>("map_shallow", shallow_);
  estimate.launch(params_.photon_count, gpu.groups().traversal);
  gpu.queue().finish();
}

void PhotonMapPass::bind(NamedKernel& kernel) const {
  kernel.set_buffer<PhotonHit>("map_photons", photons_)
      .set_buffer<cl_float4>("map_radiance", radiance_)
      .set_buffer<cl_float4>("map_shallow", shallow_)
      .set_buffer<cl_uint>("map_buckets", buckets_)
      .set("map", params_);
}

std::vector<cl_float4> PhotonMapPass::estimates() { return gpu_.download<cl_float4>(radiance_, params_.photon_count); }

std::vector<cl_float4> PhotonMapPass::shallow_estimates() {
  return gpu_.download<cl_float4>(shallow_, params_.photon_count);
}

std::vector<cl_float4> PhotonMapPass::radiance_at(const std::vector<cl_float4>& points,
                                                  const std::vector<cl_float4>& normals) {
  cl::Buffer p = gpu_.upload(points, CL_MEM_READ_ONLY, "photon lookups"), n = gpu_.upload(normals, CL_MEM_READ_ONLY, "photon lookups");
  cl::Buffer out = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(points.size(), 1) * sizeof(cl_float4), "lookups");
  NamedKernel look_up = gpu_.kernel("photon_map.cl", "look_up_photon_radiance", {});
  bind(look_up);
  look_up.set_buffer<cl_float4>("points", p)
      .set_buffer<cl_float4>("normals", n)
      .set("point_count", cl_uint(points.size()))
      .set_buffer<cl_float4>("radiance", out);
  look_up.launch(points.size(), gpu_.groups().traversal);
  return gpu_.download<cl_float4>(out, points.size());
}

}  // namespace rcsplat
