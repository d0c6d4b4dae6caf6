#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "util/error.h"


namespace rcsplat {

bool Scene::has_emissive_triangles() const {
  for (uint32_t m : triangle_material) {
    const glm::vec3& e = materials[m].emission;
    if (e.x > 0.0f || e.y > 0.0f || e.z > 0.0f) return true;
  }
  return false;
}

bool Scene::has_vertex_colors() const {
  for (const glm::vec3& c : colors)
    if (c != glm::vec3(1.0f)) return true;
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
  colors.insert(colors.end(), {glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f)});
  if (!tangents.empty()) tangents.insert(tangents.end(), 3, glm::vec4(0.0f));
  triangle_material.push_back(material);
}

void Scene::add_quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                     uint32_t material) {
  add_triangle(a, b, c, material);
  add_triangle(a, c, d, material);
}

float Scene::bounding_radius() const {
  // A scene of one point has no size: give it one unit. Any other size stands, however small (a default camera at a
  // millimetre from a micrometre-sized scene would see nothing; found by fuzzing).
  float radius = float(0.5 * glm::length(glm::dvec3(bounds_max()) - glm::dvec3(bounds_min())));
  return radius > 0.0f ? radius : 1.0f;
}

void Scene::check_extent() const {
  const double radius = 0.5 * glm::length(glm::dvec3(bounds_max()) - glm::dvec3(bounds_min()));
  if (radius == 0.0 || (radius >= 1e-15 && radius <= 1e15)) return;
  char text[200];
  std::snprintf(text, sizeof text, "the scene's bounding radius, %g units, is outside the range rcsplat renders "
                "(1e-15 to 1e15 units): rescale it", radius);
  throw Error(source + ": " + text);
}

SceneCamera Scene::default_camera() const {
  // Look at the scene's centre from the front (+z), far enough for its bounding sphere to fit a 45-degree view.
  SceneCamera cam;
  cam.name = "default";
  cam.yfov = 0.7853982f;
  cam.target = 0.5f * (bounds_min() + bounds_max());
  cam.eye = cam.target + glm::vec3(0.0f, 0.0f, bounding_radius() / std::tan(0.5f * cam.yfov) * 1.1f);
  return cam;
}

SceneLight Scene::default_light(const SceneCamera& view) const {
  // A point light a scene radius above the viewpoint (along the view's up), bright enough that a grey surface at the
  // scene's scale is visible.
  SceneLight light;
  light.name = "default";
  glm::vec3 up = glm::length(view.up) > 0.0f ? glm::normalize(view.up) : glm::vec3(0.0f, 1.0f, 0.0f);
  light.position = view.eye + up * bounding_radius();
  // In double: the square of a distance leaves single precision long before the distance does.
  double d = glm::length(glm::dvec3(light.position) - 0.5 * (glm::dvec3(bounds_min()) + glm::dvec3(bounds_max())));
  light.intensity = glm::vec3(float(d > 0.0 ? 3.0 * d * d : 3.0));
  return light;
}

}  // namespace rcsplat
