// The eight-wide BVH rcsplat traverses on the device: built with Embree's builder (SAH, high quality, spatial splits),
// flattened into the Bvh8Node / TriangleBlock8 layout of kernels/shared_types.h.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "kernels/shared_types.h"

namespace rcsplat {

struct Bvh8 {
  std::vector<Bvh8Node> nodes;         // nodes[0] is the root, always an inner node
  std::vector<TriangleBlock8> blocks;  // leaves' triangles, eight to a block
  int depth = 0;                       // inner levels on the longest root-to-leaf path
  size_t triangle_references = 0;      // triangles in leaves, counting spatial-split duplicates
  double build_seconds = 0.0;

  // Entries a traversal stack needs: each level pushes at most seven siblings.
  static int stack_size_for_depth(int depth) { return 7 * depth + 8; }
  int stack_size() const { return stack_size_for_depth(depth); }
};

// positions: three per triangle. Degenerate and non-finite triangles are left out (no ray can hit them).
Bvh8 build_bvh8(const std::vector<glm::vec3>& positions);
// Over the listed triangles alone; the leaves name them by their index in `positions`.
Bvh8 build_bvh8(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& triangles);

}  // namespace rcsplat
