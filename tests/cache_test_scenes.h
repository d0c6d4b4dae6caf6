// Scenes and device set-up shared by the irradiance cache tests.
#pragma once
#include <memory>

#include "bvh/bvh8.h"
#include "bvh/embree_scene.h"
#include "reference/host_shading.h"
#include "cl/device_scene.h"
#include "render/camera.h"
#include "corridor_scene.h"
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

}  // namespace rcsplat::test
