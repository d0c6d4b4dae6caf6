#include "cache/light_guide.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace rcsplat {
namespace {

struct Bin {
  glm::dvec3 flux{0.0}, weighted_position{0.0}, weighted_normal{0.0};
  double weight = 0.0;  // luminance of the flux
  double radius = 0.0;
};

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

glm::dvec3 load(const float* v) { return glm::dvec3(v[0], v[1], v[2]); }

// The cell and the facing (dominant axis of the normal, and its sign) of a hit: the two sides of a thin wall, or a
// floor and the wall beside it, fall in different bins.
uint64_t bin_key(const PhotonHit& p) {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    int cell = int(std::floor((double(p.position[a]) + 1.0) * 0.5 * kGuideGridCells));
    key = key * 64 + uint64_t(std::clamp(cell, -1, kGuideGridCells) + 1);
  }
  glm::dvec3 n = load(p.normal), m = glm::abs(n);
  int axis = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  return key * 6 + uint64_t(2 * axis + (n[axis] < 0.0 ? 1 : 0));
}

}  // namespace

std::vector<GuideCluster> cluster_photons(const std::vector<PhotonHit>& photons, unsigned max_clusters) {
  std::unordered_map<uint64_t, Bin> bins;
  for (const PhotonHit& p : photons) {
    if (!p.hit) continue;
    glm::dvec3 flux = load(p.flux);
    double w = luminance(flux);
    if (!(w > 0.0) || !std::isfinite(w)) continue;
    Bin& b = bins[bin_key(p)];
    b.flux += flux;
    b.weight += w;
    b.weighted_position += w * load(p.position);
    b.weighted_normal += w * load(p.normal);
  }
  for (auto& [key, b] : bins) b.weighted_position /= b.weight;
  for (const PhotonHit& p : photons) {
    if (!p.hit) continue;
    auto it = bins.find(bin_key(p));
    if (it != bins.end())
      it->second.radius = std::max(it->second.radius, glm::length(load(p.position) - it->second.weighted_position));
  }
  std::vector<const Bin*> order;
  for (auto& [key, b] : bins) order.push_back(&b);
  // Brightest first; ties by position so that the order never depends on the hash map's.
  std::sort(order.begin(), order.end(), [](const Bin* a, const Bin* b) {
    if (a->weight != b->weight) return a->weight > b->weight;
    const glm::dvec3 &p = a->weighted_position, &q = b->weighted_position;
    return p.x != q.x ? p.x < q.x : (p.y != q.y ? p.y < q.y : p.z < q.z);
  });
  order.resize(std::min<size_t>(order.size(), std::min<unsigned>(max_clusters, GUIDE_MAX_CLUSTERS)));
  // A bin's photons sample its lit area: it reaches about half the spacing between them beyond the outermost one,
  // and never less than a sixteenth of a cell (one photon alone).
  const double cell = 2.0 / kGuideGridCells;
  std::vector<GuideCluster> clusters;
  for (const Bin* b : order) {
    GuideCluster c{};
    glm::dvec3 normal = b->weighted_normal / b->weight;
    for (int a = 0; a < 3; ++a) {
      c.centre[a] = float(b->weighted_position[a]);
      c.flux[a] = float(b->flux[a]);
      c.normal[a] = float(normal[a]);
    }
    c.radius = float(std::max(b->radius * 1.1, cell / 16.0));
    clusters.push_back(c);
  }
  return clusters;
}

}  // namespace rcsplat
