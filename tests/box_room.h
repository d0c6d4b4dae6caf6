// A closed box seen from inside, for the tests' and benchmarks' generated rooms (tests/corridor_scene.h,
// tests/gap_room_scene.h); needs neither GoogleTest nor a device.
#pragma once
#include <glm/glm.hpp>

#include <string>

#include "scene/scene.h"

namespace rcsplat::test {

// The six faces of the box lo .. hi, facing inward, in a fixed order: floor (floor_material), ceiling, the walls at
// lo.x and hi.x, the far end at lo.z and the near end at hi.z (wall_material).
inline void add_inward_box(Scene& s, const glm::vec3& lo, const glm::vec3& hi, uint32_t floor_material,
                           uint32_t wall_material) {
  const float x0 = lo.x, x1 = hi.x, y0 = lo.y, h = hi.y, z0 = hi.z, z1 = lo.z;
  s.add_quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, floor_material);  // floor, facing up
  s.add_quad({x0, h, z0}, {x0, h, z1}, {x1, h, z1}, {x1, h, z0}, wall_material);       // ceiling
  s.add_quad({x0, y0, z0}, {x0, y0, z1}, {x0, h, z1}, {x0, h, z0}, wall_material);     // left wall
  s.add_quad({x1, y0, z0}, {x1, h, z0}, {x1, h, z1}, {x1, y0, z1}, wall_material);     // right wall
  s.add_quad({x0, y0, z1}, {x1, y0, z1}, {x1, h, z1}, {x0, h, z1}, wall_material);     // far end
  s.add_quad({x0, y0, z0}, {x0, h, z0}, {x1, h, z0}, {x1, y0, z0}, wall_material);     // near end
}

// A camera at eye looking at target, of vertical field of view yfov (radians), added to the scene.
inline void add_camera(Scene& s, const glm::vec3& eye, const glm::vec3& target, float yfov) {
  SceneCamera camera;
  camera.eye = eye;
  camera.target = target;
  camera.yfov = yfov;
  s.cameras.push_back(camera);
}

// A scene of the box lo .. hi seen from inside: its floor material 0 (grey 0.5), its walls and ceiling material 1
// (grey 0.7), both Lambertian; no light or camera yet.
inline Scene grey_box_room(const std::string& source, const glm::vec3& lo, const glm::vec3& hi) {
  Scene s;
  s.source = source;
  s.materials.push_back({"floor", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  s.materials.push_back({"walls", glm::vec4(0.7f, 0.7f, 0.7f, 1.0f), -1, glm::vec3(0.0f), false});
  add_inward_box(s, lo, hi, 0, 1);
  return s;
}

}  // namespace rcsplat::test
