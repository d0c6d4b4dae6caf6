// The built-in Cornell box with glTF's rough dielectric walls (a 4% lobe at roughness 1), a gold metal floor and a
// dielectric tall box at the given roughnesses: a floor below HSH_MIN_ROUGHNESS is sampled per pixel (LOBE_GLOSSY) and
// casts caustics, lobes at or above it are radiance-cached (LOBE_HSH).
#pragma once
#include <glm/glm.hpp>

#include "scene/cornell_box.h"

namespace rcsplat::test {

inline Scene cornell_box_with_lobes(float floor_roughness, float box_roughness) {
  Scene scene = make_cornell_box();
  for (SceneMaterial& m : scene.materials) m.specular = 1.0f;
  SceneMaterial floor = scene.materials[0];
  floor.name = "gold floor";
  floor.base_color = glm::vec4(0.9f, 0.7f, 0.4f, 1.0f);
  floor.metallic = 1.0f;
  floor.roughness = floor_roughness;
  SceneMaterial box = scene.materials[0];
  box.name = "glossy box";
  box.roughness = box_roughness;
  scene.materials.push_back(floor);
  scene.materials.push_back(box);
  scene.triangle_material[0] = scene.triangle_material[1] = uint32_t(scene.materials.size() - 2);
  for (size_t t = 22; t < 32; ++t) scene.triangle_material[t] = uint32_t(scene.materials.size() - 1);
  return scene;
}

}  // namespace rcsplat::test
