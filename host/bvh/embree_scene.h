// Embree's own ray tracer over the same triangles: the reference the device traversal is tested and benchmarked
// against, and the ray caster of host-side reference renderers.
#pragma once
#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <vector>

namespace rcsplat {

struct EmbreeHit {
  float t;  // tmax when nothing was hit
  float u, v;
  int prim;  // -1 when nothing was hit
};

class EmbreeScene {
 public:
  explicit EmbreeScene(const std::vector<glm::vec3>& positions);  // three per triangle
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  EmbreeHit intersect(const glm::vec3& org, const glm::vec3& dir, float tmin, float tmax) const;
  bool occluded(const glm::vec3& org, const glm::vec3& dir, float tmin, float tmax) const;

 private:
  void build(const std::vector<glm::vec3>& positions);  // fills and commits scene_; throws rcsplat::Error

  RTCScene scene_ = nullptr;
};

}  // namespace rcsplat
