// A closed cube [-0.5, 0.5]^3 (already in device units), every face of albedo 0.5, facing in, without lights: every
// photon sent inside lands, and lands again after each reflection (the light guide's and the photon map's tests).
#pragma once
#include "scene/scene.h"

namespace rcsplat::test {

inline Scene closed_cube() {
  Scene s;
  s.source = "closed cube";
  s.materials.push_back({"grey", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  const float h = 0.5f;
  s.add_quad({-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h}, 0);
  s.add_quad({-h, h, -h}, {-h, h, h}, {h, h, h}, {h, h, -h}, 0);
  s.add_quad({-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h}, 0);
  s.add_quad({h, -h, -h}, {h, h, -h}, {h, h, h}, {h, -h, h}, 0);
  s.add_quad({-h, -h, -h}, {-h, h, -h}, {h, h, -h}, {h, -h, -h}, 0);
  s.add_quad({-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}, 0);
  return s;
}

}  // namespace rcsplat::test
