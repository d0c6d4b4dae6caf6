#include "pass_probe.h"

#include "point_lookup.h"

namespace rcsplat::test {

std::vector<cl_float4> photon_radiance_at(GpuContext& gpu, const PhotonMapPass& map,
                                          const std::vector<cl_float4>& points, const std::vector<cl_float4>& normals) {
  NamedKernel look_up = gpu.kernel("photon_map.cl", "look_up_photon_radiance", {});
  map.bind(look_up);
  return run_point_lookup(gpu, look_up, points, normals, "radiance");
}

std::vector<cl_float4> caustic_irradiance_at(GpuContext& gpu, const CausticMapPass& map,
                                             const std::vector<cl_float4>& points,
                                             const std::vector<cl_float4>& normals) {
  NamedKernel look_up = gpu.kernel("caustic_map.cl", "caustic_irradiance_at", {});
  map.bind(look_up);
  return run_point_lookup(gpu, look_up, points, normals, "irradiance");
}

WorldRecordGrid download_world_record_grid(GpuContext& gpu, const DeviceWorldRecordGrid& grid) {
  WorldRecordGrid out;
  out.params = grid.params;
  out.bucket_starts = gpu.download<cl_uint>(*grid.bucket_starts, size_t(grid.params.bucket_count) + 1);
  if (out.bucket_starts.back()) out.record_lists = gpu.download<cl_uint>(*grid.record_lists, out.bucket_starts.back());
  return out;
}

std::vector<cl_float4> PassProbe::photon_estimates(PhotonMapPass& map) {
  return map.gpu_.download<cl_float4>(map.radiance_, 2 * size_t(map.params_.photon_count));
}

std::vector<cl_float4> PassProbe::shallow_photon_estimates(PhotonMapPass& map) {
  return map.gpu_.download<cl_float4>(map.shallow_, 2 * size_t(map.params_.photon_count));
}

std::vector<cl_float4> PassProbe::cached_irradiance_at(GlossyPass& glossy, const std::vector<CacheRecord>& records,
                                                       const WorldRecordGrid& grid,
                                                       const std::vector<cl_float4>& points,
                                                       const std::vector<cl_float4>& normals) {
  NamedKernel look_up = glossy.gpu_.kernel(GlossyPass::kProgram, "cached_irradiance_at", glossy.defines_);
  glossy.prepare_records({&records, &grid});
  glossy.bind_records(look_up);
  return run_point_lookup(glossy.gpu_, look_up, points, normals, "irradiance");
}

std::vector<float> PassProbe::glossy_rgba(GlossyPass& glossy) {
  return glossy.gpu_.download<float>(glossy.radiance_, glossy.pixels_ * 4);
}

}  // namespace rcsplat::test
