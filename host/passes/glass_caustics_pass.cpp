#include "passes/glass_caustics_pass.h"

#include <cmath>

#include "cache/photon_map.h"
#include "kernels/counter_random.h"
#include "passes/caustic_map_pass.h"
#include "passes/light_guide_pass.h"

namespace rcsplat {

std::vector<int> glass_caustic_levels(const std::vector<PhotonHit>& photons, float smallest, unsigned neighbours) {
  std::vector<int> level(photons.size(), GLASS_CAUSTIC_LEVELS - 1);
  std::vector<size_t> open(photons.size());
  for (size_t i = 0; i < open.size(); ++i) open[i] = i;
  float radius = smallest;
  for (int j = 0; j + 1 < GLASS_CAUSTIC_LEVELS && !open.empty(); ++j, radius *= 2.0f) {
    const PhotonGrid grid = sort_into_grid(photons, radius);
    std::vector<size_t> still_open;
    for (size_t i : open) {
      if (photon_neighbour_count(grid, photons[i]) >= neighbours) level[i] = j;
      else still_open.push_back(i);
    }
    open.swap(still_open);
  }
  return level;
}

GlassCausticMap shoot_glass_caustics(GpuContext& gpu, DeviceScene& scene, double surface_area,
                                     const GlassLight& settings) {
  GlassCausticMap map;
  map.paths = settings.photons;
  const std::vector<PhotonHit> photons = lit_landings(
      LightGuidePass(gpu, scene).shoot(settings.photons, STREAM_GLASS_CAUSTICS, 1, 0, PhotonKeep::through_glass_volume));
  map.photons = photons.size();
  // The smallest level's radius is the one where the photons crowd most (a focus), the largest 2^7 times it.
  const float start = photon_gather_radius(surface_area, photons.size(), settings.neighbours);
  map.radius = crowded_gather_radius(photons, start, settings.neighbours);
  const std::vector<int> level_of = glass_caustic_levels(photons, map.radius, settings.neighbours);
  std::vector<PhotonHit> sorted;
  std::vector<cl_uint> buckets;
  std::vector<CausticMapLevel> levels(GLASS_CAUSTIC_LEVELS);
  for (int j = 0; j < GLASS_CAUSTIC_LEVELS; ++j) {
    std::vector<PhotonHit> mine;
    for (size_t i = 0; i < photons.size(); ++i)
      if (level_of[i] == j) mine.push_back(photons[i]);
    if (mine.empty()) continue;
    const float radius = std::ldexp(map.radius, j);
    const PhotonGrid grid = sort_into_grid(mine, radius);
    levels[size_t(j)].grid = grid.params;
    levels[size_t(j)].first_photon = cl_uint(sorted.size());
    levels[size_t(j)].first_bucket = cl_uint(buckets.size());
    sorted.insert(sorted.end(), grid.photons.begin(), grid.photons.end());
    buckets.insert(buckets.end(), grid.bucket_starts.begin(), grid.bucket_starts.end());
    map.largest_radius = radius;
    map.level_photons[size_t(j)] = mine.size();
  }
  scene.set_glass_caustics(gpu, sorted, buckets, levels);
  return map;
}

void GlassCausticsPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) {
  gpu.build_ahead(kProgram, scene.defines());
}

GlassCausticsPass::GlassCausticsPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "add_glass_caustics", scene.defines())) {}

void GlassCausticsPass::add_to(const GBufferView& gbuffer, const cl::Buffer& direct) {
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set_buffer<cl_float4>("direct", direct);
  kernel_.launch(gbuffer.pixel_count(), gpu_.groups().traversal);
  gpu_.queue().finish();
}

}  // namespace rcsplat
