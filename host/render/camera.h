// From a scene camera (and command-line overrides) to the kernels' CameraParams at a resolution.
#pragma once
#include <optional>

#include "kernels/shared_types.h"
#include "scene/scene.h"

namespace rcsplat {

struct CameraOverrides {
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fov_degrees;  // vertical
};

// The scene's camera `index` with the overrides applied. Throws rcsplat::Error for a bad index or a degenerate view.
SceneCamera choose_camera(const Scene& scene, int index, const CameraOverrides& overrides);

// Width and height: as given, or derived from the other and the camera's aspect ratio (512 wide by default).
void resolve_resolution(const SceneCamera& camera, int& width, int& height);

CameraParams camera_params(const SceneCamera& camera, int width, int height);

}  // namespace rcsplat
