// Host twins of the cache's weight and usability test (kernels/cache.h), in the same float operations so that the
// octree lookup and the splat make the same decisions, and the extrapolation in double.
#pragma once
#include <glm/glm.hpp>

#include <cmath>

#include "kernels/shared_types.h"

namespace rcsplat {

constexpr float kMaxRecordWeight = 1.0e3f;  // MAX_RECORD_WEIGHT
constexpr float kInFrontTolerance = 0.05f;  // IN_FRONT_TOLERANCE

inline float ward_weight(const glm::vec3& p, const glm::vec3& n, const glm::vec3& pk, const glm::vec3& nk, float radius) {
  float denom = glm::length(p - pk) / radius + glm::length(n - nk) * 0.70710678f;
  return denom * kMaxRecordWeight > 1.0f ? 1.0f / denom : kMaxRecordWeight;
}

inline bool record_usable(float w, float accuracy, const glm::vec3& p, const glm::vec3& n, const glm::vec3& pk,
                          const glm::vec3& nk, float radius) {
  return w * accuracy > 1.0f && glm::dot(n, nk) > 0.0f && glm::dot(p - pk, n + nk) * 0.5f >= -kInFrontTolerance * radius;
}

inline glm::vec3 record_position(const CacheRecord& r) { return {r.position[0], r.position[1], r.position[2]}; }
inline glm::vec3 record_normal(const CacheRecord& r) { return {r.normal[0], r.normal[1], r.normal[2]}; }

// E_k(P) = max(0, E + (nk x n) . grad_r + (P - Pk) . grad_t), per channel, in double.
inline glm::dvec3 extrapolated_irradiance(const CacheRecord& r, const glm::dvec3& p, const glm::dvec3& n) {
  glm::dvec3 dp = p - glm::dvec3(record_position(r)), dn = glm::cross(glm::dvec3(record_normal(r)), n);
  glm::dvec3 e(r.irradiance[0], r.irradiance[1], r.irradiance[2]);
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 3; ++c)
      e[c] += dp[axis] * r.grad_translation[3 * axis + c] + dn[axis] * r.grad_rotation[3 * axis + c];
  return glm::max(e, glm::dvec3(0.0));
}

// World size of one pixel at p (kernels/cache.h pixel_world_size).
inline float pixel_world_size(const CameraParams& cam, const glm::vec3& p) {
  glm::vec3 eye(cam.eye[0], cam.eye[1], cam.eye[2]), fwd(cam.forward[0], cam.forward[1], cam.forward[2]);
  return 2.0f * std::fabs(glm::dot(p - eye, fwd)) * cam.tan_half_fov_y / float(cam.height);
}

}  // namespace rcsplat
