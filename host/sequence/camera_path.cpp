#include "sequence/camera_path.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>

#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace {

constexpr uintmax_t kMaxKeyframeFileBytes = 16u << 20;

std::string camera_name(const Scene& scene, int camera) {
  return "camera " + std::to_string(camera) + " '" + scene.cameras[size_t(camera)].name + "'";
}

bool degenerate_view(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up) {
  const glm::dvec3 forward = target - eye;
  const double f = glm::length(forward), u = glm::length(up);
  return !(f > 0.0) || !(u > 0.0) || !(glm::length(glm::cross(forward / f, up / u)) > 1e-6);
}

// Whether `animation` moves a mesh or a light of the scene.
bool animation_moves_content(const Scene& scene, int animation) {
  for (const Scene::AnimatedContent& moved : scene.animated_content)
    if (moved.animation == animation) return true;
  return false;
}

}  // namespace

CameraPath gltf_camera_path(const Scene& scene, int camera, int animation, bool scene_may_move) {
  if (scene.animation_names.empty()) throw Error(scene.source + ": the scene has no animation to play");
  if (animation < 0 || size_t(animation) >= scene.animation_names.size())
    throw Error("--animation " + std::to_string(animation) + ": " + scene.source + " has " +
                std::to_string(scene.animation_names.size()) + " animation(s)");
  for (const Scene::AnimatedContent& moved : scene.animated_content)
    if (moved.animation == animation && !scene_may_move)
      throw Error(scene.source + ": " + moved.what +
                  "; this camera path moves only the camera through a scene that stands still: " +
                  (moved.morph_weights ? std::string("morph weights are not played even with --cache-per-frame; ")
                                       : std::string("render it with --cache-per-frame, or ")) +
                  "walk through it as it stands with --keyframes or --orbit");
  if (camera < 0 || size_t(camera) >= scene.cameras.size())
    throw Error("--camera " + std::to_string(camera) + ": " + scene.source + " has " +
                std::to_string(scene.cameras.size()) + " camera(s): " + describe_cameras(scene));
  const std::string name =
      "animations[" + std::to_string(animation) + "] '" + scene.animation_names[size_t(animation)] + "'";
  const bool content_moves = scene_may_move && animation_moves_content(scene, animation);
  const bool camera_moves =
      size_t(camera) < scene.camera_rigs.size() && rig_is_animated(scene.camera_rigs[size_t(camera)], animation);
  if (!camera_moves && content_moves) {
    // A still camera watching the scene move: its rest pose (the scene's own camera, with the user's overrides).
    const SceneCamera still = scene.cameras[size_t(camera)];
    CameraPath path;
    path.description = "glTF " + name + " (moving the scene; " + camera_name(scene, camera) + " stands still)";
    path.duration = scene.animation_durations[size_t(animation)];
    path.moves_scene_animation = animation;
    path.at = [still](double) {
      CameraPose pose;
      pose.eye = still.eye;
      pose.target = still.target;
      pose.up = still.up;
      return pose;
    };
    return path;
  }
  if (!camera_moves) {
    std::string animated;
    for (size_t c = 0; c < scene.camera_rigs.size(); ++c)
      if (rig_is_animated(scene.camera_rigs[c], animation))
        animated += (animated.empty() ? "" : ", ") + camera_name(scene, int(c));
    throw Error(scene.source + ": " + name + " does not move " + camera_name(scene, camera) +
                (animated.empty() ? std::string(" nor any camera") : "; it moves " + animated + " (--camera)"));
  }
  const NodeRig rig = scene.camera_rigs[size_t(camera)];
  CameraPath path;
  path.description = "glTF " + name + " of " + camera_name(scene, camera);
  path.duration = rig_duration(rig, animation);
  if (content_moves) {
    path.duration = std::max(path.duration, scene.animation_durations[size_t(animation)]);
    path.moves_scene_animation = animation;
  }
  path.at = [rig, animation](double t) {
    const glm::mat4 world = rig_world_matrix(rig, animation, t);
    CameraPose pose;
    pose.eye = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    pose.target = pose.eye + glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));  // glTF cameras look along -z
    pose.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
    return pose;
  };
  return path;
}

std::vector<CameraKey> parse_camera_keys(const std::string& text, const std::string& source) {
  std::vector<CameraKey> keys;
  std::istringstream lines(text);
  std::string line;
  for (size_t number = 1; std::getline(lines, line); ++number) {
    const std::string where = source + ": line " + std::to_string(number);
    if (size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<double> v;
    std::string field;
    while (fields >> field) {
      char* end = nullptr;
      const double x = std::strtod(field.c_str(), &end);
      if (end == field.c_str() || *end != '\0' || !std::isfinite(x))
        throw Error(where + ": '" + printable(field.substr(0, 40)) + "' is not a finite number");
      v.push_back(x);
    }
    if (v.empty()) continue;
    if (v.size() != 11)
      throw Error(where + ": " + std::to_string(v.size()) +
                  " numbers where a key has 11 (time, eye x y z, target "
                  "x y z, up x y z, vertical field of view in degrees)");
    CameraKey k{v[0], {v[1], v[2], v[3]}, {v[4], v[5], v[6]}, {v[7], v[8], v[9]}, v[10]};
    if (!keys.empty() && !(k.time > keys.back().time))
      throw Error(where + ": time " + std::to_string(k.time) + " is not after the key before it");
    if (k.time < 0.0) throw Error(where + ": a negative time");
    if (degenerate_view(k.eye, k.target, k.up))
      throw Error(where + ": the eye, target and up do not define a view (target = eye, or up along the view)");
    if (!(k.fov_degrees > 0.0 && k.fov_degrees < 179.0))
      throw Error(where + ": the field of view must be between 0 and 179 degrees");
    keys.push_back(k);
  }
  if (keys.empty()) throw Error(source + ": no keys (a line is \"time ex ey ez tx ty tz ux uy uz fov\")");
  return keys;
}

CameraPath keyframe_camera_path(const std::vector<CameraKey>& keys, const std::string& source) {
  if (keys.empty()) throw Error(source + ": no keys");
  CameraPath path;
  path.description =
      "keyframes " + source + " (" + std::to_string(keys.size()) + " key" + (keys.size() == 1 ? "" : "s") + ")";
  path.duration = keys.back().time;
  path.at = [keys](double t) {
    const size_t n = keys.size();
    CameraPose pose;
    auto set = [&pose](const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double fov) {
      pose.eye = glm::vec3(eye);
      pose.target = glm::vec3(target);
      pose.up = glm::vec3(up);
      pose.fov_degrees = float(fov);
    };
    if (n == 1 || t <= keys.front().time) {
      set(keys.front().eye, keys.front().target, keys.front().up, keys.front().fov_degrees);
      return pose;
    }
    if (t >= keys.back().time) {
      set(keys.back().eye, keys.back().target, keys.back().up, keys.back().fov_degrees);
      return pose;
    }
    size_t k = 0;
    while (k + 2 < n && keys[k + 1].time <= t) ++k;
    // Catmull-Rom tangents over time: the slope between the neighbours (one-sided at the ends).
    auto tangent = [&keys, n](size_t i, glm::dvec3 CameraKey::*point) {
      const size_t a = i ? i - 1 : 0, b = std::min(i + 1, n - 1);
      return (keys[b].*point - keys[a].*point) / (keys[b].time - keys[a].time);
    };
    const double h = keys[k + 1].time - keys[k].time, u = (t - keys[k].time) / h, u2 = u * u, u3 = u2 * u;
    auto hermite = [&](glm::dvec3 CameraKey::*point) {
      return (2 * u3 - 3 * u2 + 1) * (keys[k].*point) + (u3 - 2 * u2 + u) * h * tangent(k, point) +
             (-2 * u3 + 3 * u2) * (keys[k + 1].*point) + (u3 - u2) * h * tangent(k + 1, point);
    };
    set(hermite(&CameraKey::eye), hermite(&CameraKey::target), keys[k].up + u * (keys[k + 1].up - keys[k].up),
        keys[k].fov_degrees + u * (keys[k + 1].fov_degrees - keys[k].fov_degrees));
    return pose;
  };
  return path;
}

CameraPath read_keyframe_camera_path(const std::string& path) {
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) throw Error(path + ": cannot read the keyframe file (" + ec.message() + ")");
  if (bytes > kMaxKeyframeFileBytes) throw Error(path + ": a keyframe file of more than 16 MiB");
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw Error(path + ": cannot read the keyframe file");
  return keyframe_camera_path(parse_camera_keys(text, path), path);
}

CameraPath orbit_camera_path(const SceneCamera& start, double seconds, double degrees) {
  if (!(seconds > 0.0) || !std::isfinite(seconds)) throw Error("--orbit: the seconds of a turn must be above 0");
  if (!(std::fabs(degrees) <= 36000.0)) throw Error("--orbit-degrees: at most 100 turns either way");
  const glm::dvec3 axis = glm::normalize(glm::dvec3(start.up)), target(start.target);
  const glm::dvec3 offset = glm::dvec3(start.eye) - target;
  const glm::dvec3 along = glm::dot(offset, axis) * axis, radial = offset - along;
  if (!(glm::length(radial) > 1e-6 * glm::length(offset)))
    throw Error("--orbit: the camera looks along its up vector, so there is no circle to move it on");
  CameraPath path;
  char text[120];
  std::snprintf(text, sizeof text, "an orbit of %g degrees in %g s around the camera's target", degrees, seconds);
  path.description = text;
  path.duration = seconds;
  path.at = [=](double t) {
    const double angle = degrees * std::numbers::pi / 180.0 * t / seconds, c = std::cos(angle), s = std::sin(angle);
    // Rodrigues' rotation of the radial part about the axis (radial is perpendicular to it).
    const glm::dvec3 turned = c * radial + s * glm::cross(axis, radial);
    CameraPose pose;
    pose.eye = glm::vec3(target + along + turned);
    pose.target = start.target;
    pose.up = start.up;
    return pose;
  };
  return path;
}

}  // namespace rcsplat
