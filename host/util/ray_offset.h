// The host's offset_ray_origin: kernels/host_device.h offset_ray_coordinate on each axis, the kernels' own bits.
#pragma once
#include <glm/glm.hpp>

#include "kernels/host_device.h"

namespace rcsplat {

inline glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n) {
  return glm::vec3(offset_ray_coordinate(p.x, n.x), offset_ray_coordinate(p.y, n.y), offset_ray_coordinate(p.z, n.z));
}

}  // namespace rcsplat
