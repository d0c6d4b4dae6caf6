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
  // Embree's packet API (rtcIntersect8 / rtcIntersect16, flagged coherent): `count` rays (at most `width`, 8 or 16)
  // from org[i], dir[i], tmin[i], tmax[i] as one packet, hits into out[0 .. count - 1]. The fairer opponent for rays
  // that share an origin (a record's hemisphere).
  void intersect_packet(int width, int count, const glm::vec3* org, const glm::vec3* dir, const float* tmin,
                        const float* tmax, EmbreeHit* out) const;
  bool occluded(const glm::vec3& org, const glm::vec3& dir, float tmin, float tmax) const;

 private:
  void build(const std::vector<glm::vec3>& positions);  // fills and commits scene_; throws rcsplat::Error

  RTCScene scene_ = nullptr;
};

}  // namespace rcsplat
