#include "bvh/bvh8.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "bvh/embree_device.h"
#include "util/error.h"

namespace rcsplat {
namespace {

constexpr unsigned kLeafTriangles = 8 * BVH_MAX_LEAF_BLOCKS;  // a leaf ref addresses at most four blocks

// Embree's builder calls back into these to make a pointer tree in its own allocator; we flatten it afterwards.
struct BuildNode {
  bool is_leaf;
  unsigned count;
};
struct BuildInner : BuildNode {
  void* children[BVH_WIDTH];
  RTCBounds bounds[BVH_WIDTH];
};
struct BuildLeaf : BuildNode {
  unsigned prims[1];  // count entries follow
};

void* create_inner(RTCThreadLocalAllocator alloc, unsigned count, void*) {
  auto* node = static_cast<BuildInner*>(rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16));
  node->is_leaf = false;
  node->count = count;
  return node;
}

void set_children(void* node_ptr, void** children, unsigned count, void*) {
  auto* node = static_cast<BuildInner*>(node_ptr);
  for (unsigned i = 0; i < count; ++i) node->children[i] = children[i];
  node->count = count;
}

void set_bounds(void* node_ptr, const RTCBounds** bounds, unsigned count, void*) {
  auto* node = static_cast<BuildInner*>(node_ptr);
  for (unsigned i = 0; i < count; ++i) node->bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  size_t bytes = sizeof(BuildLeaf) + sizeof(unsigned) * std::max<size_t>(count, 1);
  auto* leaf = static_cast<BuildLeaf*>(rtcThreadLocalAlloc(alloc, bytes, 16));
  leaf->is_leaf = true;
  leaf->count = unsigned(count);
  for (size_t i = 0; i < count; ++i) leaf->prims[i] = prims[i].primID;
  return leaf;
}

// Spatial splits: the bounds of the parts of a triangle on either side of an axis-aligned plane, clipped to the
// primitive's current bounds (which may already be a piece of the triangle).
void split_triangle(const RTCBuildPrimitive* prim, unsigned dim, float pos, RTCBounds* left, RTCBounds* right,
                    void* user) {
  const auto& positions = *static_cast<const std::vector<glm::vec3>*>(user);
  const glm::vec3* v = &positions[size_t(prim->primID) * 3];
  glm::vec3 lo_l(INFINITY), hi_l(-INFINITY), lo_r(INFINITY), hi_r(-INFINITY);
  auto add = [](glm::vec3& lo, glm::vec3& hi, const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (int i = 0; i < 3; ++i) {
    const glm::vec3& a = v[i];
    const glm::vec3& b = v[(i + 1) % 3];
    if (a[dim] <= pos) add(lo_l, hi_l, a);
    if (a[dim] >= pos) add(lo_r, hi_r, a);
    if ((a[dim] < pos && b[dim] > pos) || (a[dim] > pos && b[dim] < pos)) {
      glm::vec3 c = glm::mix(a, b, (pos - a[dim]) / (b[dim] - a[dim]));
      c[dim] = pos;
      add(lo_l, hi_l, c);
      add(lo_r, hi_r, c);
    }
  }
  glm::vec3 plo(prim->lower_x, prim->lower_y, prim->lower_z), phi(prim->upper_x, prim->upper_y, prim->upper_z);
  lo_l = glm::max(lo_l, plo);
  hi_l = glm::min(hi_l, phi);
  lo_r = glm::max(lo_r, plo);
  hi_r = glm::min(hi_r, phi);
  hi_l[dim] = std::min(hi_l[dim], pos);
  lo_r[dim] = std::max(lo_r[dim], pos);
  // Rounding can leave a clipped part outside the primitive's (already clipped) box; the builder needs non-empty
  // sides, so fall back to the box's half, which is still conservative.
  auto empty = [](const glm::vec3& lo, const glm::vec3& hi) { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; };
  if (empty(lo_l, hi_l)) {
    lo_l = plo;
    hi_l = phi;
    hi_l[dim] = std::max(plo[dim], std::min(phi[dim], pos));
  }
  if (empty(lo_r, hi_r)) {
    lo_r = plo;
    hi_r = phi;
    lo_r[dim] = std::min(phi[dim], std::max(plo[dim], pos));
  }
  *left = RTCBounds{lo_l.x, lo_l.y, lo_l.z, 0.0f, hi_l.x, hi_l.y, hi_l.z, 0.0f};
  *right = RTCBounds{lo_r.x, lo_r.y, lo_r.z, 0.0f, hi_r.x, hi_r.y, hi_r.z, 0.0f};
}

class Flattener {
 public:
  explicit Flattener(const std::vector<glm::vec3>& positions) : positions_(positions) {}

  void flatten_root(const BuildNode* root, Bvh8& out) {
    out_ = &out;
    out.nodes.emplace_back();
    init_node(out.nodes[0]);
    if (!root) {
      out.depth = 1;
      return;
    }
    if (root->is_leaf) {
      const auto* leaf = static_cast<const BuildLeaf*>(root);
      std::vector<unsigned> prims(leaf->prims, leaf->prims + leaf->count);
      set_child(0, 0, leaf_ref(prims, 2), bounds_of(prims));
      out.depth = std::max(out.depth, 1);
      return;
    }
    fill_inner(0, static_cast<const BuildInner*>(root), 1);
  }

 private:
  static void init_node(Bvh8Node& n) {
    for (int i = 0; i < 8; ++i) {
      n.lo_x[i] = n.lo_y[i] = n.lo_z[i] = INFINITY;
      n.hi_x[i] = n.hi_y[i] = n.hi_z[i] = -INFINITY;
      n.child[i] = 0;
    }
  }

  void set_child(size_t node, int slot, int ref, const RTCBounds& b) {
    Bvh8Node& n = out_->nodes[node];
    n.lo_x[slot] = b.lower_x;
    n.lo_y[slot] = b.lower_y;
    n.lo_z[slot] = b.lower_z;
    n.hi_x[slot] = b.upper_x;
    n.hi_y[slot] = b.upper_y;
    n.hi_z[slot] = b.upper_z;
    n.child[slot] = ref;
  }

  void fill_inner(size_t index, const BuildInner* src, int depth) {
    out_->depth = std::max(out_->depth, depth);
    for (unsigned i = 0; i < src->count; ++i) {
      const auto* child = static_cast<const BuildNode*>(src->children[i]);
      int ref;
      if (child->is_leaf) {
        const auto* leaf = static_cast<const BuildLeaf*>(child);
        ref = leaf_ref(std::vector<unsigned>(leaf->prims, leaf->prims + leaf->count), depth + 1);
      } else {
        ref = new_node();
        fill_inner(size_t(ref), static_cast<const BuildInner*>(child), depth + 1);
      }
      set_child(index, int(i), ref, src->bounds[i]);
    }
  }

  int new_node() {
    out_->nodes.emplace_back();
    init_node(out_->nodes.back());
    if (out_->nodes.size() > size_t(std::numeric_limits<int>::max())) throw Error("BVH too large");
    return int(out_->nodes.size() - 1);
  }

  RTCBounds bounds_of(const std::vector<unsigned>& prims) const {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (unsigned p : prims)
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, positions_[size_t(p) * 3 + k]);
        hi = glm::max(hi, positions_[size_t(p) * 3 + k]);
      }
    return RTCBounds{lo.x, lo.y, lo.z, 0.0f, hi.x, hi.y, hi.z, 0.0f};
  }

  // A leaf reference for these triangles; a leaf too large for one reference becomes an inner node over smaller ones.
  int leaf_ref(const std::vector<unsigned>& prims, int depth) {
    if (prims.size() > kLeafTriangles) {
      int node = new_node();
      out_->depth = std::max(out_->depth, depth);
      size_t chunk = std::max<size_t>((prims.size() + 7) / 8, 1);
      for (size_t start = 0, slot = 0; start < prims.size(); start += chunk, ++slot) {
        std::vector<unsigned> part(prims.begin() + long(start), prims.begin() + long(std::min(prims.size(), start + chunk)));
        int ref = leaf_ref(part, depth + 1);
        set_child(size_t(node), int(slot), ref, bounds_of(part));
      }
      return node;
    }
    size_t first = out_->blocks.size();
    size_t block_count = std::max<size_t>((prims.size() + 7) / 8, 1);
    for (size_t b = 0; b < block_count; ++b) {
      TriangleBlock8 block{};
      for (int lane = 0; lane < 8; ++lane) {
        size_t i = b * 8 + size_t(lane);
        block.prim[lane] = -1;
        if (i >= prims.size()) continue;
        const glm::vec3* v = &positions_[size_t(prims[i]) * 3];
        block.v0_x[lane] = v[0].x, block.v0_y[lane] = v[0].y, block.v0_z[lane] = v[0].z;
        block.v1_x[lane] = v[1].x, block.v1_y[lane] = v[1].y, block.v1_z[lane] = v[1].z;
        block.v2_x[lane] = v[2].x, block.v2_y[lane] = v[2].y, block.v2_z[lane] = v[2].z;
        block.prim[lane] = int(prims[i]);
      }
      out_->blocks.push_back(block);
    }
    out_->triangle_references += prims.size();
    if (first > size_t(std::numeric_limits<int>::max() >> 3)) throw Error("BVH too large");
    return ~int((first << 2) | (block_count - 1));
  }

  const std::vector<glm::vec3>& positions_;
  Bvh8* out_ = nullptr;
};

}  // namespace

Bvh8 build_bvh8(const std::vector<glm::vec3>& positions) {
  std::vector<uint32_t> all(positions.size() / 3);
  for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
  return build_bvh8(positions, all);
}

Bvh8 build_bvh8(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& triangles) {
  auto start = std::chrono::steady_clock::now();
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(triangles.size() * 2);  // spare capacity lets the builder make spatial splits
  for (const size_t t : triangles) {
    const glm::vec3 &a = positions[3 * t], &b = positions[3 * t + 1], &c = positions[3 * t + 2];
    glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    bool finite = std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(lo.z) && std::isfinite(hi.x) &&
                  std::isfinite(hi.y) && std::isfinite(hi.z);
    if (!finite || glm::length(glm::cross(b - a, c - a)) == 0.0f) continue;
    RTCBuildPrimitive p;
    p.lower_x = lo.x, p.lower_y = lo.y, p.lower_z = lo.z, p.geomID = 0;
    p.upper_x = hi.x, p.upper_y = hi.y, p.upper_z = hi.z, p.primID = unsigned(t);
    prims.push_back(p);
  }

  Bvh8 out;
  RTCBVH bvh = rtcNewBVH(embree_device());
  check_embree("creating a BVH");
  const BuildNode* root = nullptr;
  if (!prims.empty()) {
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.buildQuality = RTC_BUILD_QUALITY_HIGH;
    args.maxBranchingFactor = BVH_WIDTH;
    args.maxDepth = 48;
    args.sahBlockSize = 8;  // leaves cost by blocks of eight, as the kernel tests them
    args.minLeafSize = 1;
    args.maxLeafSize = 24;
    args.traversalCost = 2.0f;  // measured on Sponza: deeper leaves than 1.0 gives, 2-3% faster (RESULTS.md)
    args.intersectionCost = 1.0f;
    args.bvh = bvh;
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.capacity();
    args.createNode = create_inner;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    args.splitPrimitive = split_triangle;
    args.userPtr = const_cast<std::vector<glm::vec3>*>(&positions);
    root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
    try {
      check_embree("building the BVH over " + std::to_string(prims.size()) + " triangles");
    } catch (const Error&) {
      rtcReleaseBVH(bvh);
      throw;
    }
    if (!root) {
      rtcReleaseBVH(bvh);
      throw Error("Embree failed to build the BVH (rtcBuildBVH returned nothing)");
    }
  }
  Flattener(positions).flatten_root(root, out);
  rtcReleaseBVH(bvh);
  out.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rcsplat
