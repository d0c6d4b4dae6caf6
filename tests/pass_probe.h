// What tests read of a pass that no user can observe: a map's lookups at chosen points and its per-photon estimates,
// the glossy pass's raw light and its reads of the records, a device grid brought back. PassProbe is the friend the
// passes name (util/test_probe.h); the free functions need only the passes' public binding.
#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cache/world_record_grid.h"
#include "passes/caustic_map_pass.h"
#include "passes/glossy_pass.h"
#include "passes/photon_map_pass.h"
#include "passes/world_record_grid_pass.h"

namespace rcsplat::test {

// The reflected-light estimate a photon map's lookup finds at these points (xyz) on surfaces facing these normals.
std::vector<cl_float4> photon_radiance_at(GpuContext& gpu, const PhotonMapPass& map,
                                          const std::vector<cl_float4>& points, const std::vector<cl_float4>& normals);
// The caustic irradiance at these points on surfaces facing these normals.
std::vector<cl_float4> caustic_irradiance_at(GpuContext& gpu, const CausticMapPass& map,
                                             const std::vector<cl_float4>& points,
                                             const std::vector<cl_float4>& normals);
// A grid built on the device, brought back.
WorldRecordGrid download_world_record_grid(GpuContext& gpu, const DeviceWorldRecordGrid& grid);

struct PassProbe {
  // The lookup photons' estimates, in the lookup grid's order: two float4 (RGB, 0) per photon, the reflected light
  // and the irradiance, both over pi (kernels/photon_map.cl); and the same without the shallow landings.
  static std::vector<cl_float4> photon_estimates(PhotonMapPass& map);
  static std::vector<cl_float4> shallow_photon_estimates(PhotonMapPass& map);
  // What a glossy sample reads of the records at these points (xyz) with these shading normals: float4 (E, the sum
  // of the weights; 0 where no record reaches).
  static std::vector<cl_float4> cached_irradiance_at(GlossyPass& glossy, const std::vector<CacheRecord>& records,
                                                     const WorldRecordGrid& grid, const std::vector<cl_float4>& points,
                                                     const std::vector<cl_float4>& normals);
  // The glossy pass's light, float4 per pixel (RGB, rays cast).
  static std::vector<float> glossy_rgba(GlossyPass& glossy);

  // A context's programs ("file|options") asked for by program() so far, and those build_ahead started.
  static std::set<std::string> programs_asked_for(const GpuContext& gpu);
  static std::set<std::string> programs_built_ahead(const GpuContext& gpu);
  // Every kernel of every program the context built so far, and for each kernel launched whether its last launch set
  // all its parameters by name in the kernel's own order.
  static std::set<std::string> built_kernel_names(const GpuContext& gpu);
  static const std::map<std::string, bool>& launched_kernels(const GpuContext& gpu);
  // How many buffers the context has made so far.
  static size_t buffers_made(const GpuContext& gpu);
  // Another device's group sizes on this one (a GPU's record trace on PoCL must give the same records).
  static void set_groups(GpuContext& gpu, const GroupSizes& groups);
};

}  // namespace rcsplat::test
