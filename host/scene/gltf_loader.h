// Loads a glTF 2.0 file (.gltf or .glb) into a Scene. Malformed input throws rcsplat::Error naming the file and the
// problem; unsupported features are named in warnings.
#pragma once
#include <string>

#include "scene/scene.h"

namespace rcsplat {
Scene load_gltf(const std::string& path);
}
