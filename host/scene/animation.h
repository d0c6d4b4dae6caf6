// glTF node animation: the chain of nodes from a scene root down to a camera's node, or to a node that holds a mesh or
// a light (Scene::movers), each with its rest transform and the animation channels that move it, sampled at any time
// as glTF 2.0 section 3.11 says (STEP, LINEAR with spherical interpolation of rotations, CUBICSPLINE as a Hermite
// spline). scene/scene_animator.h poses the movers' triangles and lights by it.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

namespace rcsplat {

enum class AnimatedProperty { translation, rotation, scale };
enum class AnimationInterpolation { step, linear, cubic_spline };

// One channel's keys: `times` strictly increasing, seconds; `values` 3 (translation, scale) or 4 (rotation, x y z w)
// floats a key, or for a cubic spline three such elements a key: in-tangent, value, out-tangent.
struct AnimationTrack {
  int animation = 0;  // index into the glTF's animations
  AnimatedProperty property = AnimatedProperty::translation;
  AnimationInterpolation interpolation = AnimationInterpolation::linear;
  std::vector<float> times;
  std::vector<float> values;
};

// A node's local transform as glTF gives it: translation, rotation, scale.
struct NodeTrs {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
};

struct RigNode {
  std::string label;  // "nodes[3] 'CameraBoom'", for messages
  NodeTrs rest;
  bool has_matrix = false;  // a node given by a matrix (never animated: glTF animates TRS nodes only)
  glm::mat4 matrix{1.0f};
  std::vector<AnimationTrack> tracks;
};

// From a scene root (first) down to a camera's or a mover's node (last).
struct NodeRig {
  std::vector<RigNode> chain;
};

// The keys of `track` at time t (clamped to its first and last key), 3 or 4 components.
glm::vec4 sample_track(const AnimationTrack& track, double t);
// The property `track` animates, set to its value at time t.
void apply_track(const AnimationTrack& track, double t, NodeTrs& trs);
// T * R * S.
glm::mat4 trs_matrix(const NodeTrs& trs);
// The last node's world transform at time t with the channels of `animation` applied (others: the rest transform).
glm::mat4 rig_world_matrix(const NodeRig& rig, int animation, double t);
// Whether any node of the rig is moved by `animation`, and the last key time of its channels there.
bool rig_is_animated(const NodeRig& rig, int animation);
double rig_duration(const NodeRig& rig, int animation);

}  // namespace rcsplat
