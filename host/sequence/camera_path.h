// A camera path for `rcsplat animate`: where the camera is at each time of a walkthrough, from the scene's own glTF
// animation of a camera node (scene/animation.h), from a keyframe file (docs/USAGE.md "Walkthroughs", --keyframes), or an orbit
// around the chosen camera's target. A pose becomes a frame through the camera overrides (render/camera.h), so every
// frame is planned exactly as `render` plans a still one.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "scene/scene.h"

namespace rcsplat {

struct CameraPose {
  glm::vec3 eye{0.0f}, target{0.0f, 0.0f, -1.0f}, up{0.0f, 1.0f, 0.0f};
  std::optional<float> fov_degrees;  // vertical; none: the camera's own
  CameraOverrides overrides() const { return {eye, target, up, fov_degrees}; }
};

struct CameraPath {
  std::string description;  // "glTF animations[0] 'Walk' of camera 0 'Cam'", "keyframes path.txt (12 keys)", ...
  double duration = 0.0;    // seconds; frames beyond it hold the last pose
  std::function<CameraPose(double seconds)> at;
  int moves_scene_animation = -1;  // the scene's animation this path plays on meshes and lights too (-1: none)
};

// The glTF animation `animation` of the scene's camera `camera` (its node and every node above it). Throws
// rcsplat::Error when the scene has no such animation, when it moves neither that camera nor (with scene_may_move)
// anything else, or when it moves a mesh or a light and scene_may_move is false (named: one cache serves the whole
// path, so the scene must stand still unless each frame has a cache of its own). With scene_may_move the path lasts
// as long as the animation's last key, and a camera the animation does not move stands at its rest pose.
CameraPath gltf_camera_path(const Scene& scene, int camera, int animation, bool scene_may_move = false);

// One key of a keyframe file: at `time` seconds the camera is at eye, looks at target, with up and a vertical field
// of view in degrees.
struct CameraKey {
  double time = 0.0;
  glm::dvec3 eye{0.0}, target{0.0}, up{0.0, 1.0, 0.0};
  double fov_degrees = 45.0;
};
// Parses a keyframe file's text: a key a line, "time ex ey ez tx ty tz ux uy uz fov", '#' starts a comment. Throws
// rcsplat::Error naming `source` and the line for a malformed line, a time not after the one before, or a key whose
// view is degenerate (target = eye, up along the view) or whose field of view is outside (0, 179).
std::vector<CameraKey> parse_camera_keys(const std::string& text, const std::string& source);
// Eye and target move on a cubic Hermite spline through the keys with Catmull-Rom tangents over time (so the camera's
// speed has no jumps at a key), up and field of view linearly.
CameraPath keyframe_camera_path(const std::vector<CameraKey>& keys, const std::string& source);
// Reads a keyframe file (at most 16 MiB) and makes its path.
CameraPath read_keyframe_camera_path(const std::string& path);

// An arc of `degrees` (a whole turn: 360) around the vertical line (the camera's up) through its target in
// `seconds`, counter-clockwise seen from above (negative degrees: clockwise), keeping the eye's height and distance.
CameraPath orbit_camera_path(const SceneCamera& start, double seconds, double degrees = 360.0);

}  // namespace rcsplat
