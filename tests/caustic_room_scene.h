// Issue 41 item 1's case: light reflected by a glossy floor onto a diffuse wall (a caustic). Shared by the tests and
// benchmarks; needs neither GoogleTest nor a device.
#pragma once
#include <glm/glm.hpp>

#include "box_room.h"
#include "scene/scene.h"

namespace rcsplat::test {

// A closed room (4 m wide along x, 3 m high, 4 m deep; walls and ceiling grey 0.7, Lambertian) whose floor is a glossy
// metal (base 0.9, roughness `floor_roughness`: LOBE_GLOSSY below 0.45). A small lamp hangs 0.6 m above the floor,
// 1 m from the far wall; its mirror image in the floor lights the far wall and the ceiling through the floor's lobe,
// a light -> glossy -> diffuse path (the caustic), as bright there as the lamp's own light. The camera stands at the
// near end and sees the far wall, the floor and the ceiling.
inline Scene caustic_room(float floor_roughness = 0.15f) {
  Scene s = grey_box_room("room with a glossy floor", {-2.0f, 0.0f, -4.0f}, {2.0f, 3.0f, 0.0f});
  SceneMaterial& floor = s.materials[0];
  floor.name = "glossy metal floor";
  floor.base_color = glm::vec4(0.9f, 0.9f, 0.9f, 1.0f);
  floor.metallic = 1.0f;
  floor.roughness = floor_roughness;
  SceneLight lamp;
  lamp.type = LightType::point;
  lamp.position = {0.3f, 0.6f, -3.0f};
  lamp.intensity = glm::vec3(20.0f);
  s.lights.push_back(lamp);
  add_camera(s, {0.0f, 1.5f, -0.2f}, {0.0f, 1.0f, -4.0f}, 1.1f);
  return s;
}

}  // namespace rcsplat::test
