#include "pass_probe.h"

#include <chrono>
#include <sstream>

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

std::set<std::string> PassProbe::programs_asked_for(const GpuContext& gpu) {
  std::lock_guard<std::mutex> lock(gpu.programs_mutex_);
  return gpu.asked_for_;
}

std::set<std::string> PassProbe::programs_built_ahead(const GpuContext& gpu) {
  std::lock_guard<std::mutex> lock(gpu.programs_mutex_);
  return gpu.built_ahead_;
}

std::set<std::string> PassProbe::built_kernel_names(const GpuContext& gpu) {
  std::vector<GpuContext::ProgramFuture> programs;
  {
    std::lock_guard<std::mutex> lock(gpu.programs_mutex_);
    for (const auto& [key, future] : gpu.programs_) programs.push_back(future);
  }
  std::set<std::string> names;
  for (const GpuContext::ProgramFuture& future : programs) {
    if (future.wait_for(std::chrono::seconds(0)) == std::future_status::deferred) continue;  // never asked for
    std::shared_ptr<cl::Program> program;
    try {
      program = future.get();
    } catch (const std::exception&) {
      continue;  // a build that failed has no kernels
    }
    std::istringstream list(program->getInfo<CL_PROGRAM_KERNEL_NAMES>());
    for (std::string name; std::getline(list, name, ';');) {
      while (!name.empty() && (name.back() == '\0' || name.back() == ' ')) name.pop_back();
      if (!name.empty()) names.insert(name);
    }
  }
  return names;
}

const std::map<std::string, bool>& PassProbe::launched_kernels(const GpuContext& gpu) { return gpu.launched_; }

size_t PassProbe::buffers_made(const GpuContext& gpu) { return gpu.buffers_made_; }

void PassProbe::set_groups(GpuContext& gpu, const GroupSizes& groups) { gpu.groups_ = groups; }

}  // namespace rcsplat::test
