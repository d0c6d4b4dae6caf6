#include "cache/record_octree.h"

#include <algorithm>

namespace rcsplat {

RecordOctree::RecordOctree(const glm::dvec3& lo, const glm::dvec3& hi) {
  glm::dvec3 extent = hi - lo;
  double half = 0.5 * std::max({extent.x, extent.y, extent.z, 1e-6}) * 1.001;
  Node root{0.5 * (lo + hi), half, {}, {}};
  root.child.fill(-1);
  nodes_.push_back(root);
}

void RecordOctree::insert(uint32_t record, const glm::dvec3& position, double reach) {
  int32_t index = 0;
  // Descend while the child around the position is still at least as large as the reach; positions outside the root
  // stay at the root, whose test then decides.
  for (;;) {
    Node& node = nodes_[size_t(index)];
    double child_half = 0.5 * node.half;
    glm::dvec3 d = position - node.center;
    if (child_half < reach || glm::any(glm::greaterThan(glm::abs(d), glm::dvec3(node.half))) || child_half < 1e-9) break;
    int octant = (d.x > 0 ? 1 : 0) | (d.y > 0 ? 2 : 0) | (d.z > 0 ? 4 : 0);
    if (node.child[size_t(octant)] < 0) {
      glm::dvec3 offset((octant & 1 ? 1 : -1) * child_half, (octant & 2 ? 1 : -1) * child_half,
                        (octant & 4 ? 1 : -1) * child_half);
      Node child{node.center + offset, child_half, {}, {}};
      child.child.fill(-1);
      nodes_[size_t(index)].child[size_t(octant)] = int32_t(nodes_.size());
      nodes_.push_back(child);  // may move the nodes: re-read by index below
    }
    index = nodes_[size_t(index)].child[size_t(octant)];
  }
  nodes_[size_t(index)].records.push_back(record);
}

}  // namespace rcsplat
