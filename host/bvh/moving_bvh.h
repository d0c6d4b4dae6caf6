// A BVH for a scene whose parts move rigidly (issue 62): the still triangles keep one tree, built once; each moving
// part keeps a tree of its own, built once and refitted when it moves; a small top level over the parts' boxes is made
// again each time. All of it is one Bvh8 in the layout kernels/traverse.h walks: the top level's nodes come first (the
// root is node 0), and its children are the parts' roots, so the traversal needs no second kind of node and a still
// scene, which never gets one, keeps its bits.
//
// Why refit and not rebuild: a part's tree keeps its shape, so the device buffers keep their sizes and only the
// part's rows are written again; a translation leaves every box as tight as the build made it, and a rotation loosens
// them by at most the rotated box's growth (benchmarks/RESULTS.md, "Issue 62", measures what a moving part costs).
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <utility>
#include <functional>
#include <vector>

#include "bvh/bvh8.h"

namespace rcsplat {

struct TriangleRange {
  size_t first = 0, count = 0;
};

class MovingBvh {
 public:
  // positions: three per triangle, every triangle of the scene (device coordinates). Each range is one moving part;
  // ranges must not overlap. The rest is still.
  MovingBvh(const std::vector<glm::vec3>& positions, const std::vector<TriangleRange>& parts);

  const Bvh8& tree() const { return tree_; }

  // Rows of the tree a move rewrote: [first, first + count) of nodes and of blocks.
  struct Rows {
    size_t first = 0, count = 0;
  };
  struct Changed {
    std::vector<Rows> nodes, blocks;
    // For each moved part, the box it filled before and after the move, joined: lowest and highest corner.
    std::vector<std::pair<glm::vec3, glm::vec3>> swept;
    // For each moved part of at most kListedTriangles triangles, its triangles before the move and then after (three
    // corners each); empty for a larger part.
    std::vector<std::vector<glm::vec3>> triangles;
  };
  static constexpr size_t kListedTriangles = 64;
  // The parts listed (indices into the ranges given at construction) moved: `vertex(i)` gives vertex i's position
  // (3 a triangle, the scene's numbering) and is asked only for the moved parts' vertices; their triangles are written
  // into their blocks, their boxes refitted, and the top level made again.
  Changed move(const std::function<glm::vec3(size_t vertex)>& vertex, const std::vector<size_t>& moved);
  Changed move(const std::vector<glm::vec3>& positions, const std::vector<size_t>& moved) {
    return move([&positions](size_t i) { return positions[i]; }, moved);
  }

 private:
  struct Part {
    TriangleRange triangles;
    size_t node_first = 0, node_count = 0, block_first = 0, block_count = 0;
  };
  void build_top();

  Bvh8 tree_;
  size_t top_nodes_ = 0;
  std::vector<Part> parts_;  // parts_[0]: the still triangles; then the moving parts in the order given
};

}  // namespace rcsplat
