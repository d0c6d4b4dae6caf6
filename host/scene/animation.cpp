#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace rcsplat {
namespace {

size_t components(const AnimationTrack& track) { return track.property == AnimatedProperty::rotation ? 4 : 3; }

// Key k's value (for a cubic spline, the middle element of its three), or its in- (-1) or out-tangent (+1).
glm::dvec4 key_element(const AnimationTrack& track, size_t k, int which = 0) {
  const size_t n = components(track);
  const bool cubic = track.interpolation == AnimationInterpolation::cubic_spline;
  const size_t first = cubic ? (3 * k + size_t(1 + which)) * n : k * n;
  glm::dvec4 v(0.0);
  for (size_t c = 0; c < n; ++c) v[int(c)] = double(track.values[first + c]);
  return v;
}

glm::dvec4 normalized(glm::dvec4 q) {
  const double length = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return length > 0.0 ? q / length : glm::dvec4(0.0, 0.0, 0.0, 1.0);
}

// Spherical interpolation along the shorter arc (x y z w), as glTF asks of LINEAR rotations.
glm::dvec4 slerp(glm::dvec4 a, glm::dvec4 b, double u) {
  double cosine = glm::dot(a, b);
  if (cosine < 0.0) {
    b = -b;
    cosine = -cosine;
  }
  if (cosine > 1.0 - 1e-9) return normalized(a + u * (b - a));  // nearly equal: the chord is the arc
  const double angle = std::acos(std::min(cosine, 1.0));
  return (std::sin((1.0 - u) * angle) * a + std::sin(u * angle) * b) / std::sin(angle);
}

}  // namespace

glm::vec4 sample_track(const AnimationTrack& track, double t) {
  const size_t keys = track.times.size();
  const bool rotation = track.property == AnimatedProperty::rotation;
  if (keys == 0) return glm::vec4(0.0f);
  if (!(t > double(track.times.front())) || keys == 1) return glm::vec4(key_element(track, 0));
  if (t >= double(track.times.back())) return glm::vec4(key_element(track, keys - 1));
  const size_t k = size_t(std::upper_bound(track.times.begin(), track.times.end(), float(t)) - track.times.begin()) - 1;
  const double t0 = track.times[k], t1 = track.times[k + 1], span = t1 - t0;
  const double u = std::clamp((t - t0) / span, 0.0, 1.0);
  glm::dvec4 v;
  switch (track.interpolation) {
    case AnimationInterpolation::step:
      v = key_element(track, k);
      break;
    case AnimationInterpolation::linear:
      v = rotation ? slerp(key_element(track, k), key_element(track, k + 1), u)
                   : key_element(track, k) + u * (key_element(track, k + 1) - key_element(track, k));
      break;
    case AnimationInterpolation::cubic_spline: {
      const double u2 = u * u, u3 = u2 * u;
      v = (2 * u3 - 3 * u2 + 1) * key_element(track, k) + (u3 - 2 * u2 + u) * span * key_element(track, k, +1) +
          (-2 * u3 + 3 * u2) * key_element(track, k + 1) + (u3 - u2) * span * key_element(track, k + 1, -1);
      if (rotation) v = normalized(v);
      break;
    }
  }
  return glm::vec4(v);
}

glm::mat4 rig_world_matrix(const NodeRig& rig, int animation, double t) {
  glm::mat4 world(1.0f);
  for (const RigNode& node : rig.chain) {
    if (node.has_matrix) {
      world = world * node.matrix;
      continue;
    }
    NodeTrs trs = node.rest;
    for (const AnimationTrack& track : node.tracks)
      if (track.animation == animation) apply_track(track, t, trs);
    world = world * trs_matrix(trs);
  }
  return world;
}

void apply_track(const AnimationTrack& track, double t, NodeTrs& trs) {
  const glm::vec4 v = sample_track(track, t);
  if (track.property == AnimatedProperty::translation)
    trs.translation = glm::vec3(v);
  else if (track.property == AnimatedProperty::scale)
    trs.scale = glm::vec3(v);
  else
    trs.rotation = glm::normalize(glm::quat(v.w, v.x, v.y, v.z));
}

glm::mat4 trs_matrix(const NodeTrs& trs) {
  return glm::translate(glm::mat4(1.0f), trs.translation) * glm::mat4_cast(trs.rotation) *
         glm::scale(glm::mat4(1.0f), trs.scale);
}

bool rig_is_animated(const NodeRig& rig, int animation) {
  for (const RigNode& node : rig.chain)
    for (const AnimationTrack& track : node.tracks)
      if (track.animation == animation) return true;
  return false;
}

double rig_duration(const NodeRig& rig, int animation) {
  double last = 0.0;
  for (const RigNode& node : rig.chain)
    for (const AnimationTrack& track : node.tracks)
      if (track.animation == animation && !track.times.empty()) last = std::max(last, double(track.times.back()));
  return last;
}

}  // namespace rcsplat
