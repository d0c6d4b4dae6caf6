#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace {

// v / |v| without overflow or underflow in |v|^2 (scenes in any unit, found by fuzzing); zero stays zero.
glm::vec3 unit(glm::vec3 v) {
  float largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (!(largest > 0.0f) || !std::isfinite(largest)) return glm::vec3(0.0f);
  v /= largest;
  return v / glm::length(v);
}

}  // namespace


std::string describe_cameras(const Scene& scene) {
  if (scene.cameras.empty()) return "no cameras";
  std::string list;
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const SceneCamera& c = scene.cameras[i];
    list += (i ? ", " : "") + std::to_string(i) + " '" + c.name + "' (" + (c.orthographic ? "orthographic" : "perspective") + ")";
  }
  return list;
}

SceneCamera choose_camera(const Scene& scene, int index, const CameraOverrides& o) {
  if (index < 0 || size_t(index) >= scene.cameras.size()) {
    throw Error("--camera " + std::to_string(index) + ": " + scene.source + " has " + std::to_string(scene.cameras.size()) +
                " camera(s): " + describe_cameras(scene));
  }
  SceneCamera c = scene.cameras[size_t(index)];
  if (o.eye || o.target) {
    glm::vec3 forward = glm::normalize(c.target - c.eye);
    glm::vec3 eye = o.eye.value_or(c.eye);
    c.target = o.target.value_or(eye + forward);
    c.eye = eye;
  }
  if (o.up) c.up = *o.up;
  if (o.fov_degrees && c.orthographic)
    throw Error("--fov: camera " + std::to_string(index) + " ('" + c.name + "') is orthographic, it has no field of view");
  if (o.fov_degrees) {
    if (!(*o.fov_degrees > 0.0f && *o.fov_degrees < 179.0f)) throw Error("--fov must be between 0 and 179 degrees");
    c.yfov = glm::radians(*o.fov_degrees);
  }
  glm::vec3 forward = unit(c.target - c.eye), up = unit(c.up);
  if (!(glm::length(forward) > 0.5f) || !(glm::length(up) > 0.5f) || !(glm::length(glm::cross(forward, up)) > 1e-6f))
    throw Error("the camera's eye, target and up do not define a view (target = eye, or up parallel to the view)");
  return c;
}

void add_view_defaults(Scene& scene, int index, const CameraOverrides& o) {
  if (scene.cameras.empty()) {
    SceneCamera camera = scene.default_camera();
    if (o.eye && !o.target) camera.eye = *o.eye;  // from the given eye, still at the scene's centre
    scene.cameras.push_back(camera);
    if (!(o.eye && o.target))
      log_warning(scene.source + ": the scene has no camera; " +
                  (o.eye ? std::string("looking from --eye at the scene's centre")
                         : o.target ? std::string("looking at --target from a default viewpoint")
                                    : std::string("using a default camera looking at the scene's centre along -z")));
  }
  if (scene.lights.empty() && !scene.has_emissive_triangles() && !scene.environment.present()) {
    SceneCamera view = choose_camera(scene, index, o);
    scene.lights.push_back(scene.default_light(view));
    log_warning(scene.source + ": the scene has no light; using a default point light above the camera");
  }
}

void resolve_resolution(const SceneCamera& camera, int& width, int& height) {
  float aspect = camera.aspect.value_or(1.0f);
  if (width <= 0 && height <= 0) width = 512;
  if (width <= 0) width = std::max(1, int(std::lround(float(height) * aspect)));
  if (height <= 0) height = std::max(1, int(std::lround(float(width) / aspect)));
  if (width > 16384 || height > 16384) throw Error("the resolution is limited to 16384 x 16384");
}

CameraParams camera_params(const SceneCamera& camera, int width, int height) {
  glm::vec3 forward = unit(camera.target - camera.eye);
  glm::vec3 right = unit(glm::cross(forward, unit(camera.up)));
  glm::vec3 up = glm::cross(right, forward);
  CameraParams p{};
  for (int i = 0; i < 3; ++i) {
    p.eye[i] = camera.eye[i];
    p.forward[i] = forward[i];
    p.right[i] = right[i];
    p.up[i] = up[i];
  }
  p.tan_half_fov_y = camera.orthographic ? 0.0f : std::tan(0.5f * camera.yfov);
  p.orthographic = camera.orthographic ? 1 : 0;
  p.half_height = camera.orthographic ? camera.ymag : 0.0f;
  p.aspect = float(width) / float(height);
  p.width = width;
  p.height = height;
  p.jitter_cell = 1.0f;  // rays through the pixels' centres
  return p;
}

}  // namespace rcsplat
