#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/log.h"

namespace rcsplat {

bool Scene::has_emissive_triangles() const {
  for (uint32_t m : triangle_material) {
    const glm::vec3& e = materials[m].emission;
    if (e.x > 0.0f || e.y > 0.0f || e.z > 0.0f) return true;
  }
  return false;
}

glm::vec3 Scene::bounds_min() const {
  glm::vec3 lo(std::numeric_limits<float>::max());
  for (const glm::vec3& p : positions) lo = glm::min(lo, p);
  return positions.empty() ? glm::vec3(0.0f) : lo;
}

glm::vec3 Scene::bounds_max() const {
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3& p : positions) hi = glm::max(hi, p);
  return positions.empty() ? glm::vec3(0.0f) : hi;
}

void Scene::add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint32_t material) {
  glm::vec3 n = glm::cross(b - a, c - a);
  float len = glm::length(n);
  n = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
  positions.insert(positions.end(), {a, b, c});
  normals.insert(normals.end(), {n, n, n});
  uvs.insert(uvs.end(), {glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)});
  triangle_material.push_back(material);
}

void Scene::add_defaults_where_missing() {
  glm::vec3 lo = bounds_min(), hi = bounds_max();
  glm::vec3 center = 0.5f * (lo + hi);
  float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  if (cameras.empty()) {
    // Look at the scene's centre from the front (+z), far enough for its bounding sphere to fit a 45-degree view.
    SceneCamera cam;
    cam.yfov = 0.7853982f;
    cam.target = center;
    cam.eye = center + glm::vec3(0.0f, 0.0f, radius / std::tan(0.5f * cam.yfov) * 1.1f);
    cameras.push_back(cam);
    log_warning(source + ": the scene has no camera; using a default camera looking at the scene's centre along -z");
  }
  if (lights.empty() && !has_emissive_triangles()) {
    // A point light at the default viewpoint's side, bright enough that a grey surface at the scene's scale is visible.
    SceneLight light;
    light.name = "default";
    light.position = cameras.front().eye + glm::vec3(0.0f, radius, 0.0f);
    float d = glm::length(light.position - center);
    light.intensity = glm::vec3(d * d * 3.0f);
    lights.push_back(light);
    log_warning(source + ": the scene has no light; using a default point light above the camera");
  }
}

}  // namespace rcsplat
