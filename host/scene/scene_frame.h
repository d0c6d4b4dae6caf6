// The coordinates the device traces and shades in: the scene's bounding box centred on the origin and scaled by a
// power of two to a radius in [0.5, 1). Single precision then spends its bits on the scene rather than on where it
// sits, so an architectural model a hundred kilometres from its origin, or a scene in millimetres or in kilometres,
// renders as it would at the origin in metres: ray offsets and every other tolerance in the kernels are sized for a
// unit scene, and a power-of-two scale changes no mantissa.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "kernels/shared_types.h"
#include "scene/scene.h"

namespace rcsplat {

struct SceneFrame {
  glm::dvec3 centre{0.0};
  double scale = 1.0;  // world units per device unit (a power of two)

  // The frame that fits the scene's bounding box (the identity for an empty or non-finite one).
  static SceneFrame fitted(const Scene& scene);

  glm::vec3 to_device(const glm::vec3& world) const { return glm::vec3((glm::dvec3(world) - centre) / scale); }
  glm::vec3 to_world(const glm::vec3& device) const { return glm::vec3(glm::dvec3(device) * scale + centre); }
  float length_to_world(float device) const { return float(double(device) * scale); }

  std::vector<glm::vec3> device_positions(const Scene& scene) const;
  SceneCamera device_camera(SceneCamera camera) const;
  // Point and spot intensities (candela) scale with the inverse square of the unit so that irradiance is unchanged;
  // a directional light's illuminance and emitted radiance do not depend on the unit.
  SceneLight device_light(SceneLight light) const;
  // A copy of the whole scene in this frame's coordinates (a scene already in its fitted frame renders with the
  // identity: tests that compare the device's records with host code in world units use it).
  Scene device_scene(Scene scene) const;
  // A record from the device frame to world units: position, radii, pixel size, translational gradients.
  CacheRecord world_record(CacheRecord record) const;
};

}  // namespace rcsplat
