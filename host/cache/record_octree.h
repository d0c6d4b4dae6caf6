// The classic irradiance cache's spatial index (Ward et al. 1988): a loose octree over record positions. A record
// lives in the deepest node, around its position, at least as large as its reach a * R, so a lookup at P only visits
// the nodes whose doubled box contains P.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace rcsplat {

class RecordOctree {
 public:
  RecordOctree(const glm::dvec3& lo, const glm::dvec3& hi);

  void insert(uint32_t record, const glm::dvec3& position, double reach);

  // Calls f(record) for every record whose reach sphere may contain p (a superset: the caller tests the weight).
  template <typename F>
  void for_each_reaching(const glm::dvec3& p, F&& f) const {
    visit(0, [&](const Node& node) {
      return glm::all(glm::lessThanEqual(glm::abs(p - node.center), glm::dvec3(2.0 * node.half)));
    }, f);
  }

  // Calls f(record) for every record whose position may lie within radius of c.
  template <typename F>
  void for_each_near(const glm::dvec3& c, double radius, F&& f) const {
    visit(0, [&](const Node& node) {
      glm::dvec3 d = glm::max(glm::abs(c - node.center) - glm::dvec3(node.half), glm::dvec3(0.0));
      return glm::dot(d, d) <= radius * radius;
    }, f);
  }

 private:
  struct Node {
    glm::dvec3 center;
    double half;
    std::array<int32_t, 8> child;
    std::vector<uint32_t> records;
  };

  template <typename Test, typename F>
  void visit(int32_t index, const Test& test, F& f) const {
    const Node& node = nodes_[size_t(index)];
    if (index != 0 && !test(node)) return;  // the root also holds records outside its box
    for (uint32_t r : node.records) f(r);
    for (int32_t c : node.child)
      if (c >= 0) visit(c, test, f);
  }

  std::vector<Node> nodes_;
};

}  // namespace rcsplat
