// Loads a glTF 2.0 file (.gltf or .glb) into a Scene. Malformed input throws rcsplat::Error naming the file and the
// problem; unsupported features are named in warnings.
#pragma once
#include <string>

#include "scene/scene.h"
#include "scene/scene_limits.h"

namespace rcsplat {

// The moment of an animation to place the scene at: each node that `animation` moves takes its channels' values at
// `time` (seconds, clamped to the keys), every other node its rest transform. animation -1: the rest pose. Morph
// weight channels are not played: a pose of an animation that has one is refused.
struct ScenePose {
  int animation = -1;
  double time = 0.0;
  // The caller plays the file's animation itself (`animate` along the glTF's own animation): the rest pose is where
  // it starts, not an animation left unplayed, so the loader notes none as not simulated.
  bool played_by_caller = false;
};

// Reads only what `limits` allows: files inside the scene's folder, triangles and host memory within bounds.
Scene load_gltf(const std::string& path, const SceneLimits& limits = {}, const ScenePose& pose = {});

}  // namespace rcsplat
