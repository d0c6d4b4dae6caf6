#include "scene/scene_animator.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace rcsplat {

SceneAnimator::SceneAnimator(const Scene& scene, int animation) : animation_(animation) {
  const std::string name = animation >= 0 && size_t(animation) < scene.animation_names.size()
                               ? "animation " + std::to_string(animation) + " '" + scene.animation_names[size_t(animation)] + "'"
                               : "animation " + std::to_string(animation);
  for (const Scene::AnimatedContent& c : scene.animated_content)
    if (c.animation == animation && c.morph_weights)
      throw Error(scene.source + ": " + c.what + "; one cache follows rigid moves only (give --cache-per-frame)");
  for (size_t m = 0; m < scene.movers.size(); ++m) {
    const Scene::Mover& mover = scene.movers[m];
    for (int a : mover.skin_animations)
      if (a == animation)
        throw Error(scene.source + ": " + name + " moves the joints of " + mover.label +
                    "'s skin, which deforms its mesh; one cache follows rigid moves only (give --cache-per-frame)");
    if (!rig_is_animated(mover.rig, animation)) continue;
    if (mover.first_triangle + mover.triangle_count > scene.triangle_count())
      throw Error(scene.source + ": " + mover.label + "'s triangles are out of range");
    Placed p;
    const auto first = long(mover.first_triangle * 3), end = long((mover.first_triangle + mover.triangle_count) * 3);
    p.positions.assign(scene.positions.begin() + first, scene.positions.begin() + end);
    p.normals.assign(scene.normals.begin() + first, scene.normals.begin() + end);
    if (!scene.tangents.empty()) p.tangents.assign(scene.tangents.begin() + first, scene.tangents.begin() + end);
    if (mover.light >= 0) p.light = scene.lights[size_t(mover.light)];
    if (!p.positions.empty()) {
      p.lo = p.hi = glm::dvec3(p.positions[0]);
      for (const glm::vec3& v : p.positions) p.lo = glm::min(p.lo, glm::dvec3(v)), p.hi = glm::max(p.hi, glm::dvec3(v));
    }
    moving_.push_back(m);
    displacement_.push_back(0.0);
    placed_.push_back(std::move(p));
    transform_.push_back(glm::dmat4(1.0));
  }
}

glm::dmat4 SceneAnimator::transform_at(const Scene& scene, size_t i, double t) const {
  const Scene::Mover& mover = scene.movers[moving_[i]];
  const glm::dmat4 m = glm::dmat4(rig_world_matrix(mover.rig, animation_, t)) * glm::inverse(glm::dmat4(mover.placed));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        throw Error(scene.source + ": " + mover.label + " has no finite transform at t = " + std::to_string(t) + " s");
  if (glm::determinant(glm::dmat3(m)) <= 0.0)
    throw Error(scene.source + ": " + mover.label + " is mirrored or flattened at t = " + std::to_string(t) +
                " s, which turns its triangles inside out; one cache follows rigid moves only (give --cache-per-frame)");
  return m;
}

SceneAnimator::Between SceneAnimator::between(const Scene& scene, size_t i, double t0, double t1) const {
  const glm::dmat4 a = transform_at(scene, i, t0), b = transform_at(scene, i, t1);
  Between out;
  out.moved = a != b;
  const Placed& p = placed_[i];
  if (p.positions.empty()) return out;
  out.lo = glm::dvec3(INFINITY);
  out.hi = glm::dvec3(-INFINITY);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec4 c((corner & 1) ? p.hi.x : p.lo.x, (corner & 2) ? p.hi.y : p.lo.y, (corner & 4) ? p.hi.z : p.lo.z,
                       1.0);
    const glm::dvec3 ca(a * c), cb(b * c);
    out.lo = glm::min(out.lo, glm::min(ca, cb));
    out.hi = glm::max(out.hi, glm::max(ca, cb));
    out.displacement = std::max(out.displacement, glm::length(cb - ca));
  }
  return out;
}

void SceneAnimator::check(const Scene& scene, double t) const {
  for (size_t i = 0; i < moving_.size(); ++i) (void)transform_at(scene, i, t);
}

std::vector<size_t> SceneAnimator::pose(Scene& scene, double t) {
  std::vector<size_t> changed;
  for (size_t i = 0; i < moving_.size(); ++i) {
    const Scene::Mover& mover = scene.movers[moving_[i]];
    const glm::dmat4 m = transform_at(scene, i, t);
    if (m == transform_[i]) continue;
    const glm::dmat3 linear(m);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    const Placed& p = placed_[i];
    const size_t first = mover.first_triangle * 3;
    for (size_t v = 0; v < p.positions.size(); ++v) {
      scene.positions[first + v] = glm::vec3(m * glm::dvec4(glm::dvec3(p.positions[v]), 1.0));
      scene.normals[first + v] = glm::vec3(glm::normalize(normal_matrix * glm::dvec3(p.normals[v])));
      if (!p.tangents.empty()) {
        const glm::dvec3 tangent = linear * glm::dvec3(p.tangents[v]);
        const double length = glm::length(tangent);
        scene.tangents[first + v] = glm::vec4(length > 0.0 ? glm::vec3(tangent / length) : glm::vec3(0.0f), p.tangents[v].w);
      }
    }
    if (mover.light >= 0) {
      SceneLight& light = scene.lights[size_t(mover.light)];
      light.position = glm::vec3(m * glm::dvec4(glm::dvec3(p.light.position), 1.0));
      const glm::dvec3 direction = linear * glm::dvec3(p.light.direction);
      if (glm::length(direction) > 0.0) light.direction = glm::vec3(glm::normalize(direction));
    }
    double displacement = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec4 c((corner & 1) ? p.hi.x : p.lo.x, (corner & 2) ? p.hi.y : p.lo.y, (corner & 4) ? p.hi.z : p.lo.z,
                         1.0);
      displacement = std::max(displacement, glm::length(glm::dvec3(m * c - transform_[i] * c)));
    }
    displacement_[i] = displacement;
    transform_[i] = m;
    changed.push_back(i);
  }
  return changed;
}

}  // namespace rcsplat
