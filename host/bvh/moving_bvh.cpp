#include "bvh/moving_bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace rcsplat {
namespace {

struct Box {
  glm::vec3 lo{INFINITY}, hi{-INFINITY};
  void add(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void add(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
};

bool slot_used(const Bvh8Node& n, int slot) { return n.lo_x[slot] <= n.hi_x[slot]; }

Box slot_box(const Bvh8Node& n, int slot) {
  Box b;
  if (slot_used(n, slot)) {
    b.lo = {n.lo_x[slot], n.lo_y[slot], n.lo_z[slot]};
    b.hi = {n.hi_x[slot], n.hi_y[slot], n.hi_z[slot]};
  }
  return b;
}

void set_slot(Bvh8Node& n, int slot, int ref, const Box& b) {
  n.lo_x[slot] = b.lo.x, n.lo_y[slot] = b.lo.y, n.lo_z[slot] = b.lo.z;
  n.hi_x[slot] = b.hi.x, n.hi_y[slot] = b.hi.y, n.hi_z[slot] = b.hi.z;
  n.child[slot] = ref;
}

Bvh8Node empty_node() {
  Bvh8Node n{};
  for (int i = 0; i < 8; ++i) set_slot(n, i, 0, Box{});
  return n;
}

Box node_box(const Bvh8Node& n) {
  Box b;
  for (int i = 0; i < 8; ++i) b.add(slot_box(n, i));
  return b;
}

// The top level over the parts: one node for up to eight, else the parts sorted along the widest axis of their
// centres and cut into eight runs of near-equal length, each run a node of its own (or the part itself, alone). The
// number of nodes depends on the number of parts alone, so a part's rows never shift.
struct TopItem {
  int ref;
  Box box;
};
int add_top_node(std::vector<Bvh8Node>& top, std::vector<TopItem> items, int level, int& depth) {
  depth = std::max(depth, level);
  const size_t index = top.size();
  top.push_back(empty_node());
  if (items.size() > 8) {
    Box centres;
    for (const TopItem& item : items) centres.add(0.5f * (item.box.lo + item.box.hi));
    const glm::vec3 extent = centres.hi - centres.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    std::stable_sort(items.begin(), items.end(), [axis](const TopItem& a, const TopItem& b) {
      return (a.box.lo[axis] + a.box.hi[axis]) < (b.box.lo[axis] + b.box.hi[axis]);
    });
  }
  const size_t n = items.size(), runs = std::min<size_t>(n, 8);
  for (size_t r = 0; r < runs; ++r) {
    const size_t begin = r * n / runs, end = (r + 1) * n / runs;
    if (end - begin == 1) {
      set_slot(top[index], int(r), items[begin].ref, items[begin].box);
      continue;
    }
    std::vector<TopItem> run(items.begin() + long(begin), items.begin() + long(end));
    Box box;
    for (const TopItem& item : run) box.add(item.box);
    const int child = add_top_node(top, std::move(run), level + 1, depth);
    set_slot(top[index], int(r), child, box);
  }
  return int(index);
}

}  // namespace

MovingBvh::MovingBvh(const std::vector<glm::vec3>& positions, const std::vector<TriangleRange>& parts) {
  const auto start = std::chrono::steady_clock::now();
  const size_t triangles = positions.size() / 3;
  std::vector<char> moving(triangles, 0);
  for (const TriangleRange& r : parts) {
    if (r.first > triangles || r.count > triangles - r.first) throw Error("a moving part's triangles are out of range");
    for (size_t t = r.first; t < r.first + r.count; ++t) {
      if (moving[t]) throw Error("two moving parts share a triangle");
      moving[t] = 1;
    }
  }
  std::vector<uint32_t> still;
  for (size_t t = 0; t < triangles; ++t)
    if (!moving[t]) still.push_back(uint32_t(t));
  std::vector<Bvh8> trees;
  trees.push_back(build_bvh8(positions, still));
  parts_.push_back(Part{TriangleRange{0, 0}});
  for (const TriangleRange& r : parts) {
    std::vector<uint32_t> list(r.count);
    for (size_t i = 0; i < r.count; ++i) list[i] = uint32_t(r.first + i);
    trees.push_back(build_bvh8(positions, list));
    parts_.push_back(Part{r});
  }
  // The top level's size first (it depends on the number of parts only), then each part's rows after it.
  std::vector<Bvh8Node> top;
  std::vector<TopItem> items(trees.size(), TopItem{0, Box{}});
  int top_depth = 0;
  add_top_node(top, items, 1, top_depth);
  top_nodes_ = top.size();
  tree_.nodes.assign(top_nodes_, empty_node());
  int part_depth = 0;
  for (size_t p = 0; p < trees.size(); ++p) {
    Bvh8& t = trees[p];
    Part& part = parts_[p];
    part.node_first = tree_.nodes.size();
    part.node_count = t.nodes.size();
    part.block_first = tree_.blocks.size();
    part.block_count = t.blocks.size();
    for (Bvh8Node& n : t.nodes)
      for (int i = 0; i < 8; ++i) {
        if (!slot_used(n, i)) continue;
        if (n.child[i] >= 0) {
          n.child[i] += int(part.node_first);
        } else {
          const int leaf = ~n.child[i];
          const size_t first = size_t(leaf >> 2) + part.block_first;
          if (first > size_t(std::numeric_limits<int>::max() >> 3)) throw Error("BVH too large");
          n.child[i] = ~int((first << 2) | size_t(leaf & 3));
        }
      }
    if (tree_.nodes.size() + t.nodes.size() > size_t(std::numeric_limits<int>::max())) throw Error("BVH too large");
    tree_.nodes.insert(tree_.nodes.end(), t.nodes.begin(), t.nodes.end());
    tree_.blocks.insert(tree_.blocks.end(), t.blocks.begin(), t.blocks.end());
    tree_.triangle_references += t.triangle_references;
    part_depth = std::max(part_depth, t.depth);
  }
  tree_.depth = top_depth + part_depth;
  build_top();
  tree_.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void MovingBvh::build_top() {
  std::vector<TopItem> items;
  for (const Part& p : parts_) items.push_back({int(p.node_first), node_box(tree_.nodes[p.node_first])});
  std::vector<Bvh8Node> top;
  int depth = 0;
  add_top_node(top, std::move(items), 1, depth);
  if (top.size() != top_nodes_) throw Error("the BVH's top level changed size");  // cannot happen: sized by count
  std::copy(top.begin(), top.end(), tree_.nodes.begin());
}

MovingBvh::Changed MovingBvh::move(const std::function<glm::vec3(size_t vertex)>& vertex, const std::vector<size_t>& moved) {
  Changed changed;
  for (const size_t m : moved) {
    if (m + 1 >= parts_.size()) throw Error("no such moving part");
    const Part& part = parts_[m + 1];
    Box swept = node_box(tree_.nodes[part.node_first]);
    const bool listed = part.triangles.count <= kListedTriangles;
    std::vector<glm::vec3> before, after;
    for (size_t b = part.block_first; b < part.block_first + part.block_count; ++b) {
      TriangleBlock8& block = tree_.blocks[b];
      for (int lane = 0; lane < 8; ++lane) {
        if (block.prim[lane] < 0) continue;
        const size_t first = size_t(block.prim[lane]) * 3;
        const glm::vec3 v[3] = {vertex(first), vertex(first + 1), vertex(first + 2)};
        if (listed) {
          before.insert(before.end(), {glm::vec3(block.v0_x[lane], block.v0_y[lane], block.v0_z[lane]),
                                       glm::vec3(block.v1_x[lane], block.v1_y[lane], block.v1_z[lane]),
                                       glm::vec3(block.v2_x[lane], block.v2_y[lane], block.v2_z[lane])});
          after.insert(after.end(), v, v + 3);
        }
        block.v0_x[lane] = v[0].x, block.v0_y[lane] = v[0].y, block.v0_z[lane] = v[0].z;
        block.v1_x[lane] = v[1].x, block.v1_y[lane] = v[1].y, block.v1_z[lane] = v[1].z;
        block.v2_x[lane] = v[2].x, block.v2_y[lane] = v[2].y, block.v2_z[lane] = v[2].z;
      }
    }
    // Children come after their parents (the flattening is depth first), so one pass from the last node up.
    for (size_t n = part.node_first + part.node_count; n-- > part.node_first;) {
      Bvh8Node& node = tree_.nodes[n];
      for (int i = 0; i < 8; ++i) {
        if (!slot_used(node, i)) continue;
        Box box;
        if (node.child[i] >= 0) {
          box = node_box(tree_.nodes[size_t(node.child[i])]);
        } else {
          const int leaf = ~node.child[i];
          const size_t first = size_t(leaf >> 2), count = size_t(leaf & 3) + 1;
          for (size_t b = first; b < first + count; ++b)
            for (int lane = 0; lane < 8; ++lane) {
              const TriangleBlock8& block = tree_.blocks[b];
              if (block.prim[lane] < 0) continue;
              // The block's lanes, written above (a part's leaves are its own blocks).
              box.add(glm::vec3(block.v0_x[lane], block.v0_y[lane], block.v0_z[lane]));
              box.add(glm::vec3(block.v1_x[lane], block.v1_y[lane], block.v1_z[lane]));
              box.add(glm::vec3(block.v2_x[lane], block.v2_y[lane], block.v2_z[lane]));
            }
        }
        set_slot(node, i, node.child[i], box);
      }
    }
    swept.add(node_box(tree_.nodes[part.node_first]));
    changed.swept.emplace_back(swept.lo, swept.hi);
    before.insert(before.end(), after.begin(), after.end());
    changed.triangles.push_back(std::move(before));
    changed.nodes.push_back({part.node_first, part.node_count});
    changed.blocks.push_back({part.block_first, part.block_count});
  }
  build_top();
  changed.nodes.push_back({0, top_nodes_});
  return changed;
}

}  // namespace rcsplat
