#include "passes/glass_caustics_pass.h"

#include <algorithm>
#include <cmath>

#include "cache/photon_map.h"
#include "kernels/counter_random.h"
#include "passes/caustic_map_pass.h"
#include "passes/light_guide_pass.h"

namespace rcsplat {

namespace {
constexpr float kGlassCausticSmallestRadius = 1e-3f;  // device units: the scene fits a sphere of radius 1
}  // namespace

std::vector<cl_float4> glass_volume_spheres(const Scene& scene, const SceneFrame& frame) {
  constexpr size_t kMaxSpheres = GLASS_CAUSTIC_LEVELS;
  std::vector<int> sphere_of(scene.materials.size(), -1);
  std::vector<glm::vec3> lo, hi;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const SceneMaterial& material = scene.materials[m];
    if (!(material.transmission > 0.0f) || material.metallic >= 1.0f || !(material.thickness > 0.0f)) continue;
    sphere_of[m] = int(std::min(lo.size(), kMaxSpheres - 1));
    if (lo.size() < kMaxSpheres) {
      lo.push_back(glm::vec3(INFINITY));
      hi.push_back(glm::vec3(-INFINITY));
    }
  }
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const int s = sphere_of[scene.triangle_material[t]];
    if (s < 0) continue;
    for (int v = 0; v < 3; ++v) {
      const glm::vec3 p = frame.to_device(scene.positions[3 * t + size_t(v)]);
      lo[size_t(s)] = glm::min(lo[size_t(s)], p);
      hi[size_t(s)] = glm::max(hi[size_t(s)], p);
    }
  }
  // About each box's centre, the farthest vertex: a ball's own sphere, where the box's half diagonal would be 1.7 times
  // wider and waste most photons.
  std::vector<float> radius(lo.size(), 0.0f);
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const int s = sphere_of[scene.triangle_material[t]];
    if (s < 0) continue;
    const glm::vec3 centre = 0.5f * (lo[size_t(s)] + hi[size_t(s)]);
    for (int v = 0; v < 3; ++v)
      radius[size_t(s)] =
          std::max(radius[size_t(s)], glm::length(frame.to_device(scene.positions[3 * t + size_t(v)]) - centre));
  }
  std::vector<cl_float4> spheres;
  for (size_t s = 0; s < lo.size(); ++s) {
    if (!(lo[s].x <= hi[s].x)) continue;  // a material no triangle uses
    const glm::vec3 centre = 0.5f * (lo[s] + hi[s]);
    // A hair wider, so that rounding never leaves a vertex outside.
    spheres.push_back(cl_float4{{centre.x, centre.y, centre.z, radius[s] * 1.001f + 1e-6f}});
  }
  return spheres;
}

std::vector<int> glass_caustic_levels(const std::vector<PhotonHit>& photons, float smallest, unsigned neighbours) {
  std::vector<int> level(photons.size(), GLASS_CAUSTIC_LEVELS - 1);
  std::vector<size_t> open(photons.size());
  for (size_t i = 0; i < open.size(); ++i) open[i] = i;
  float radius = smallest;
  for (int j = 0; j + 1 < GLASS_CAUSTIC_LEVELS && !open.empty(); ++j, radius *= 2.0f) {
    const PhotonGrid grid = sort_into_grid(photons, radius);
    std::vector<size_t> still_open;
    for (size_t i : open) {
      if (photon_neighbour_count(grid, photons[i], neighbours) >= neighbours) level[i] = j;
      else still_open.push_back(i);
    }
    open.swap(still_open);
  }
  return level;
}

GlassCausticMap shoot_glass_caustics(GpuContext& gpu, DeviceScene& scene, double surface_area,
                                     const std::vector<cl_float4>& volumes, const GlassLight& settings) {
  GlassCausticMap map;
  map.paths = settings.photons;
  LightGuidePass lights(gpu, scene);
  lights.aim_at(volumes);
  const std::vector<PhotonHit> photons =
      lit_landings(lights.shoot(settings.photons, STREAM_GLASS_CAUSTICS, 1, 0, PhotonKeep::through_glass_volume));
  map.photons = photons.size();
  // The smallest level's radius is the one where the photons crowd most (a focus), but not below a thousandth of the
  // scene's size (the device frame's unit), which a pixel's sample points could only hit or miss; the largest 2^7
  // times it.
  const float start = photon_gather_radius(surface_area, photons.size(), settings.neighbours);
  map.radius = std::max(crowded_gather_radius(photons, start, settings.neighbours), kGlassCausticSmallestRadius);
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
    // Cells twice the radius wide: a lookup visits the 2 x 2 x 2 nearest (kernels/caustic_map.h).
    const PhotonGrid grid = sort_into_grid(mine, 2.0f * radius);
    levels[size_t(j)].grid = grid.params;
    levels[size_t(j)].grid.radius = radius;
    levels[size_t(j)].first_photon = cl_uint(sorted.size());
    levels[size_t(j)].first_bucket = cl_uint(buckets.size());
    for (int a = 0; a < 3; ++a) {
      float lo = INFINITY, hi = -INFINITY;
      for (const PhotonHit& p : mine) lo = std::min(lo, p.position[a]), hi = std::max(hi, p.position[a]);
      levels[size_t(j)].reach_min[a] = lo - radius;
      levels[size_t(j)].reach_max[a] = hi + radius;
    }
    sorted.insert(sorted.end(), grid.photons.begin(), grid.photons.end());
    buckets.insert(buckets.end(), grid.bucket_starts.begin(), grid.bucket_starts.end());
    map.largest_radius = radius;
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
