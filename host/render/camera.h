// From a scene camera (and command-line overrides) to the kernels' CameraParams at a resolution.
#pragma once
#include <optional>
#include <string>

#include "kernels/shared_types.h"
#include "scene/scene.h"

namespace rcsplat {

struct CameraOverrides {
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fov_degrees;  // vertical
};

// The scene's camera `index` with the overrides applied. Throws rcsplat::Error for a bad index (the message lists the
// scene's cameras), --fov on an orthographic camera, or a degenerate view.
SceneCamera choose_camera(const Scene& scene, int index, const CameraOverrides& overrides);
// "0 'Front' (perspective), 1 'Top' (orthographic)".
std::string describe_cameras(const Scene& scene);

// A camera and a light for a scene that lacks them, following what the user gave: a view the command line describes
// completely (--eye and --target) gets no warning about a default camera, and the default light sits above the camera
// actually used (after --camera, --eye, --target and --up), so that what the camera sees is lit.
void add_view_defaults(Scene& scene, int index, const CameraOverrides& overrides);

// Width and height: as given, or derived from the other and the camera's aspect ratio (512 wide by default).
void resolve_resolution(const SceneCamera& camera, int& width, int& height);

CameraParams camera_params(const SceneCamera& camera, int width, int height);

}  // namespace rcsplat
