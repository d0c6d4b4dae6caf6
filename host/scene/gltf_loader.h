// Loads a glTF 2.0 file (.gltf or .glb) into a Scene. Malformed input throws rcsplat::Error naming the file and the
// problem; unsupported features are named in warnings.
#pragma once
#include <string>

#include "scene/scene.h"
#include "scene/scene_limits.h"

namespace rcsplat {
// Reads only what `limits` allows: files inside the scene's folder, triangles and host memory within bounds.
Scene load_gltf(const std::string& path, const SceneLimits& limits = {});
}
