// Poses a scene's movers (Scene::movers) at any time of one glTF animation without reading the file again (issue 62):
// each mover's triangles and light go by the rigid transform from where the loader placed them to where the animation
// puts them, its chain's world transform at that time times the inverse of the one it was placed with. What no rigid
// transform follows (a skin whose joints the animation moves, morph weights) is refused here, with the animation and
// what it deforms named; `animate --cache-per-frame` loads each frame's pose for those.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

#include "scene/scene.h"

namespace rcsplat {

class SceneAnimator {
 public:
  // scene: as the loader read it (its movers where it placed them).
  SceneAnimator(const Scene& scene, int animation);

  // Moves `scene` (the one given above, or a copy of it) into the animation's pose at time t, seconds. Returns the
  // movers (indices into `moving()`) whose transform changed since the last pose; on the first call, those not where
  // the loader placed them.
  std::vector<size_t> pose(Scene& scene, double t);

  // Throws what pose would throw at time t (a transform that is not finite, or mirrors or flattens a mover), moving
  // nothing: a walkthrough checks every frame's time before it writes its first frame.
  void check(const Scene& scene, double t) const;

  // Moving mover i from time t0 to time t1, world units (the poses need not be the last one): the box its triangles
  // fill at either time (the transformed corners of their box as placed), joined; how far any of their points moved;
  // and whether it moved at all (a mover without triangles, a light alone, has an empty box). Cache files' records hold
  // the times they were made at; this is how far the scene moved since (sequence/record_times.h).
  struct Between {
    glm::dvec3 lo{0.0}, hi{0.0};
    double displacement = 0.0;
    bool moved = false;
  };
  Between between(const Scene& scene, size_t i, double t0, double t1) const;

  // The movers this animation moves: indices into Scene::movers.
  const std::vector<size_t>& moving() const { return moving_; }
  // How far the last pose moved moving mover i's triangles at most, world units: the largest move of a corner of
  // their box as placed (a rigid transform moves no point of a box farther than its farthest corner).
  double last_displacement(size_t i) const { return displacement_[i]; }

 private:
  struct Placed {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> tangents;  // empty when the scene has none
    SceneLight light;
    glm::dvec3 lo{0.0}, hi{0.0};  // the triangles' box
  };
  // Moving mover i's transform from placed to posed at time t, checked.
  glm::dmat4 transform_at(const Scene& scene, size_t i, double t) const;
  int animation_;
  std::vector<size_t> moving_;
  std::vector<Placed> placed_;          // a moving mover's triangles and light as the loader placed them
  std::vector<glm::dmat4> transform_;   // each moving mover's last transform from placed to posed
  std::vector<double> displacement_;    // and how far its last pose moved it
};

}  // namespace rcsplat
