// Ray sets for the traversal benchmark and tests: cosine-distributed rays leaving surface points that the camera
// sees, as hemisphere sampling for irradiance records will cast them.
#pragma once
#include <vector>

#include "bvh/embree_scene.h"
#include "kernels/shared_types.h"
#include "scene/scene.h"

namespace rcsplat {

inline glm::vec3 ray_origin(const RayDesc& r) { return {r.origin[0], r.origin[1], r.origin[2]}; }
inline glm::vec3 ray_direction(const RayDesc& r) { return {r.direction[0], r.direction[1], r.direction[2]}; }

struct SurfaceSample {
  glm::vec3 position, normal;  // normal: geometric, facing the camera
};

// Up to `count` points hit by rays through random pixels of camera 0 (misses are retried a bounded number of times).
std::vector<SurfaceSample> camera_visible_points(const Scene& scene, const EmbreeScene& embree, size_t count,
                                                 uint32_t seed);

// Pattern A: one cosine-distributed ray from each point (incoherent).
std::vector<RayDesc> incoherent_hemisphere_rays(const std::vector<SurfaceSample>& points, uint32_t seed);
// Pattern B: strata x strata stratified cosine-distributed rays from each point (a record's hemisphere).
std::vector<RayDesc> record_hemisphere_rays(const std::vector<SurfaceSample>& points, int strata, uint32_t seed);

}  // namespace rcsplat
