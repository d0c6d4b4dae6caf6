// Host-side shading in double precision over Embree rays: what a hemisphere ray sees after one bounce, the same
// integral kernels/bounce.h estimates. Used by the classic octree irradiance cache and by the tests' references.
#pragma once
#include <glm/glm.hpp>

#include "bvh/embree_scene.h"
#include "scene/packed_scene.h"

namespace rcsplat {

class HostShading {
 public:
  HostShading(const PackedScene& scene, const EmbreeScene& embree) : scene_(scene), embree_(embree) {}

  // Radiance arriving at origin from dir after one diffuse reflection of direct light; (u, v) pick the light sample.
  // *distance: the hit distance, infinity on a miss.
  glm::dvec3 bounce_radiance(const glm::vec3& origin, const glm::dvec3& dir, double u, double v, double* distance) const;

  // Irradiance at p (shading normal n, geometric normal ng) from every punctual light and one emitter sample.
  glm::dvec3 direct_irradiance(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& ng, double u, double v) const;

  // Base colour at barycentrics (u, v) of a triangle, textured as the device does it.
  glm::dvec3 albedo(int triangle, double u, double v) const;

 private:
  bool visible(const glm::vec3& from, const glm::vec3& to_offset, float tmax) const;

  const PackedScene& scene_;
  const EmbreeScene& embree_;
};

}  // namespace rcsplat
