// Scenes and device set-up shared by the irradiance cache tests.
#pragma once
#include <cmath>
#include <memory>

#include "bvh/bvh8.h"
#include "bvh/embree_scene.h"
#include "cache/host_shading.h"
#include "cl/device_scene.h"
#include "render/camera.h"
#include "scene/scene.h"
#include "test_support.h"

namespace rcsplat::test {

// A scene on the device and on the host (Embree, double-precision shading) at once.
struct TwinScene {
  explicit TwinScene(Scene s)
      : scene(std::move(s)),
        bvh(build_bvh8(scene.positions)),
        device(gpu(), scene, bvh),
        packed(pack_scene(scene)),
        embree(std::make_unique<EmbreeScene>(scene.positions)),
        shading(packed, *embree) {}
  Scene scene;
  Bvh8 bvh;
  DeviceScene device;
  PackedScene packed;
  std::unique_ptr<EmbreeScene> embree;
  HostShading shading;
};

// A floor (z = 0, albedo 0.5) beside a wall (x = 1, albedo 0.8) lit by a point light: the floor's indirect light comes
// from the wall and varies smoothly. With occluder, a black panel at x = 0.6 over y > 0 hides part of the wall from
// floor points near y = 0: an occlusion edge.
inline Scene floor_and_wall(bool occluder) {
  Scene s;
  s.source = occluder ? "floor, wall and occluder" : "floor and wall";
  s.materials.push_back({"floor", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  s.materials.push_back({"wall", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), -1, glm::vec3(0.0f), false});
  s.materials.push_back({"black", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), -1, glm::vec3(0.0f), false});
  s.add_triangle({-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, 0);
  s.add_triangle({-10, -10, 0}, {10, 10, 0}, {-10, 10, 0}, 0);
  s.add_triangle({1, -10, 0}, {1, 10, 10}, {1, 10, 0}, 1);
  s.add_triangle({1, -10, 0}, {1, -10, 10}, {1, 10, 10}, 1);
  if (occluder) {
    s.add_triangle({0.6f, 0, 0}, {0.6f, 10, 0.4f}, {0.6f, 10, 0}, 2);
    s.add_triangle({0.6f, 0, 0}, {0.6f, 0, 0.4f}, {0.6f, 10, 0.4f}, 2);
  }
  SceneLight light;
  light.type = LightType::point;
  light.position = {0.2f, 0.0f, 3.0f};
  light.intensity = glm::vec3(4.0f);
  s.lights.push_back(light);
  add_view_defaults(s, 0, {});
  return s;
}

// A closed corridor (10 x 2 x 2.5 m, grey) lit by one 1e6 cd spot whose cone reaches only a disc of radius 0.25 m
// on the floor near the far end: every wall, and the ceiling, is lit only by the light that patch reflects. Cosine
// sampling of a record's hemisphere finds the patch in some records and misses it in others: each one that finds it
// becomes a bright disc on the walls (the blotches of issue 10). benchmarks/hard_cases/bright_patch_corridor.py
// writes the same scene as glTF.
inline Scene bright_patch_corridor() {
  Scene s;
  s.source = "bright-patch corridor";
  s.materials.push_back({"floor", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  s.materials.push_back({"walls", glm::vec4(0.7f, 0.7f, 0.7f, 1.0f), -1, glm::vec3(0.0f), false});
  const float x0 = -1.0f, x1 = 1.0f, h = 2.5f, z1 = -10.0f;
  auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t m) {
    s.add_triangle(a, b, c, m);
    s.add_triangle(a, c, d, m);
  };
  quad({x0, 0, 0}, {x1, 0, 0}, {x1, 0, z1}, {x0, 0, z1}, 0);  // floor, facing up
  quad({x0, h, 0}, {x0, h, z1}, {x1, h, z1}, {x1, h, 0}, 1);  // ceiling
  quad({x0, 0, 0}, {x0, 0, z1}, {x0, h, z1}, {x0, h, 0}, 1);  // left wall
  quad({x1, 0, 0}, {x1, h, 0}, {x1, h, z1}, {x1, 0, z1}, 1);  // right wall
  quad({x0, 0, z1}, {x1, 0, z1}, {x1, h, z1}, {x0, h, z1}, 1);  // far end
  quad({x0, 0, 0}, {x0, h, 0}, {x1, h, 0}, {x1, 0, 0}, 1);      // near end, behind the camera
  SceneLight spot;
  spot.type = LightType::spot;
  spot.position = {0.4f, 2.4f, -7.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.intensity = glm::vec3(1e6f);
  spot.inner_cone = 0.0f;
  spot.outer_cone = std::atan(0.25f / 2.4f);
  s.lights.push_back(spot);
  SceneCamera camera;
  camera.eye = {0.0f, 1.2f, -0.2f};
  camera.target = {0.0f, 1.2f, -5.0f};
  camera.yfov = 1.0f;
  s.cameras.push_back(camera);
  return s;
}

}  // namespace rcsplat::test
