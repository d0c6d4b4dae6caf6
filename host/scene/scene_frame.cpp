#include "scene/scene_frame.h"

#include <cmath>
#include <limits>

namespace rcsplat {

SceneFrame SceneFrame::fitted(const Scene& scene) {
  SceneFrame frame;
  if (scene.positions.empty()) return frame;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  for (const glm::vec3& p : scene.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  double radius = 0.5 * glm::length(hi - lo);
  glm::dvec3 centre = 0.5 * (lo + hi);
  if (!std::isfinite(radius) || !std::isfinite(centre.x + centre.y + centre.z)) return frame;
  frame.centre = centre;
  // radius / scale in [0.5, 1): frexp's exponent e has radius = m * 2^e with m in [0.5, 1).
  int exponent = 0;
  if (radius > 0.0) std::frexp(radius, &exponent);
  frame.scale = std::ldexp(1.0, exponent);
  return frame;
}

std::vector<glm::vec3> SceneFrame::device_positions(const Scene& scene) const {
  std::vector<glm::vec3> out(scene.positions.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = to_device(scene.positions[i]);
  return out;
}

SceneCamera SceneFrame::device_camera(SceneCamera camera) const {
  camera.eye = to_device(camera.eye);
  camera.target = to_device(camera.target);
  camera.xmag = float(camera.xmag / scale);
  camera.ymag = float(camera.ymag / scale);
  return camera;
}

SceneLight SceneFrame::device_light(SceneLight light) const {
  light.position = to_device(light.position);
  light.range = float(light.range / scale);
  if (light.type != LightType::directional) light.intensity = glm::vec3(glm::dvec3(light.intensity) / (scale * scale));
  return light;
}

Scene SceneFrame::device_scene(Scene scene) const {
  for (glm::vec3& p : scene.positions) p = to_device(p);
  for (SceneLight& l : scene.lights) l = device_light(l);
  for (SceneCamera& c : scene.cameras) c = device_camera(c);
  return scene;
}

CacheRecord SceneFrame::world_record(CacheRecord r) const {
  glm::vec3 p = to_world(glm::vec3(r.position[0], r.position[1], r.position[2]));
  for (int k = 0; k < 3; ++k) r.position[k] = p[k];
  r.radius = length_to_world(r.radius);
  r.pixel_size = length_to_world(r.pixel_size);
  r.harmonic_distance = length_to_world(r.harmonic_distance);
  for (float& h : r.horizon) h = length_to_world(h);
  for (float& g : r.grad_translation) g = float(double(g) / scale);
  return r;
}

}  // namespace rcsplat
