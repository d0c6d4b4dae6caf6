// Issue 41's room lit through a gap: the case where photons are scarce. Shared by the tests and
// benchmarks/gap_room.cpp; needs neither GoogleTest nor a device.
#pragma once
#include <glm/glm.hpp>

#include "box_room.h"
#include "scene/scene.h"

namespace rcsplat::test {

// A closed room (6 m wide along x, 3 m high, 4 m deep, grey walls of albedo 0.7, floor 0.5) split across its width by
// a wall that stops gap_height above the floor. A 200 W-equivalent point lamp stands on the far side, behind the
// wall; the camera stands on the near side and looks at the wall. The near side is lit only through the gap: the lamp
// reaches a strip of the near floor directly, and everything else there takes its light from surfaces on the far side
// seen under the wall, after two, three or more reflections. A photon map built from the lamp keeps few photons on the
// near side (most land behind the wall), which is what issue 41 item 4 is about; architectural interiors lit through
// doors and windows are lit the same way.
inline Scene gap_lit_room(float gap_height = 0.3f) {
  const float x0 = -3.0f, x1 = 3.0f, h = 3.0f, wall = -2.0f, thick = 0.1f;
  Scene s = grey_box_room("room lit through a gap", {x0, 0.0f, -4.0f}, {x1, h, 0.0f});  // the camera near z = 0
  // The dividing wall, a slab from gap_height to the ceiling: its near face, far face and bottom edge.
  const float zn = wall + thick / 2, zf = wall - thick / 2, g = gap_height;
  s.add_quad({x0, g, zn}, {x1, g, zn}, {x1, h, zn}, {x0, h, zn}, 1);  // near face, facing the camera
  s.add_quad({x0, g, zf}, {x0, h, zf}, {x1, h, zf}, {x1, g, zf}, 1);  // far face, facing the lamp
  s.add_quad({x0, g, zn}, {x0, g, zf}, {x1, g, zf}, {x1, g, zn}, 1);  // underside, facing the floor
  SceneLight lamp;
  lamp.type = LightType::point;
  lamp.position = {0.0f, 2.0f, -3.2f};
  lamp.intensity = glm::vec3(200.0f);
  s.lights.push_back(lamp);
  add_camera(s, {0.0f, 1.5f, -0.2f}, {0.0f, 1.0f, -2.0f}, 1.2f);
  return s;
}

}  // namespace rcsplat::test
