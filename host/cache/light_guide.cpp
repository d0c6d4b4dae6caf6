#include "cache/light_guide.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "util/colour.h"

namespace rcsplat {
namespace {

glm::dvec3 load(const float* v) { return glm::dvec3(v[0], v[1], v[2]); }

// A photon hit's grid cell and facing (dominant axis of the normal and its sign): the two sides of a thin wall, or a
// floor and the wall beside it, fall in different bins.
struct BinCoord {
  std::array<int, 3> cell;
  int facing;
};

BinCoord bin_coord(const PhotonHit& p) {
  BinCoord c{};
  for (int a = 0; a < 3; ++a)
    c.cell[a] = std::clamp(int(std::floor((double(p.position[a]) + 1.0) * 0.5 * kGuideGridCells)), -1, kGuideGridCells);
  glm::dvec3 n = load(p.normal), m = glm::abs(n);
  int axis = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  c.facing = 2 * axis + (n[axis] < 0.0 ? 1 : 0);
  return c;
}

uint64_t bin_key(const BinCoord& c) {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a) key = key * 64 + uint64_t(c.cell[a] + 1);
  return key * 6 + uint64_t(c.facing);
}

struct Region {
  glm::dvec3 flux{0.0}, weighted_position{0.0}, weighted_normal{0.0};
  double weight = 0.0;  // luminance of the flux
  double square_distances = 0.0;  // flux-weighted squared distances of the photons from the centroid
};

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<GuideCluster> cluster_photons(const std::vector<PhotonHit>& photons, unsigned max_clusters) {
  // Bins: flux per cell and facing.
  std::unordered_map<uint64_t, int> bin_of_key;
  std::vector<BinCoord> coords;
  std::vector<double> bin_flux;
  std::vector<int> photon_bin(photons.size(), -1);
  for (size_t i = 0; i < photons.size(); ++i) {
    const PhotonHit& p = photons[i];
    double w = luminance(load(p.flux));
    if (!p.hit || !(w > 0.0) || !std::isfinite(w)) continue;
    BinCoord c = bin_coord(p);
    auto [it, added] = bin_of_key.try_emplace(bin_key(c), int(coords.size()));
    if (added) {
      coords.push_back(c);
      bin_flux.push_back(0.0);
    }
    bin_flux[size_t(it->second)] += w;
    photon_bin[i] = it->second;
  }
  // Regions: neighbouring bins (26-neighbourhood) of the same facing and similar brightness (flux within a factor
  // kRegionFluxRatio) join, so that a wall lit evenly becomes one large region, which cosine sampling serves well,
  // while a small patch much brighter than its surroundings stays a region of its own.
  constexpr double kRegionFluxRatio = 8.0;
  std::vector<int> parent(coords.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t b = 0; b < coords.size(); ++b)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          BinCoord n = coords[b];
          n.cell = {n.cell[0] + dx, n.cell[1] + dy, n.cell[2] + dz};
          auto it = bin_of_key.find(bin_key(n));
          if (it == bin_of_key.end()) continue;
          double ratio = bin_flux[b] / bin_flux[size_t(it->second)];
          if (ratio > kRegionFluxRatio || ratio < 1.0 / kRegionFluxRatio) continue;
          int a = find_root(parent, int(b)), c = find_root(parent, it->second);
          if (a != c) parent[size_t(std::max(a, c))] = std::min(a, c);  // the root is the lowest bin: order-free
        }
  std::vector<Region> regions(coords.size());
  for (size_t i = 0; i < photons.size(); ++i) {
    if (photon_bin[i] < 0) continue;
    Region& r = regions[size_t(find_root(parent, photon_bin[i]))];
    glm::dvec3 flux = load(photons[i].flux);
    double w = luminance(flux);
    r.flux += flux;
    r.weight += w;
    r.weighted_position += w * load(photons[i].position);
    r.weighted_normal += w * load(photons[i].normal);
  }
  for (Region& r : regions)
    if (r.weight > 0.0) r.weighted_position /= r.weight;
  for (size_t i = 0; i < photons.size(); ++i) {
    if (photon_bin[i] < 0) continue;
    Region& r = regions[size_t(find_root(parent, photon_bin[i]))];
    glm::dvec3 offset = load(photons[i].position) - r.weighted_position;
    r.square_distances += luminance(load(photons[i].flux)) * glm::dot(offset, offset);
  }
  std::vector<const Region*> order;
  for (const Region& r : regions)
    if (r.weight > 0.0) order.push_back(&r);
  // Brightest first; ties by position so that the order never depends on the hash map's.
  std::sort(order.begin(), order.end(), [](const Region* a, const Region* b) {
    if (a->weight != b->weight) return a->weight > b->weight;
    const glm::dvec3 &p = a->weighted_position, &q = b->weighted_position;
    return p.x != q.x ? p.x < q.x : (p.y != q.y ? p.y < q.y : p.z < q.z);
  });
  order.resize(std::min<size_t>(order.size(), std::min<unsigned>(max_clusters, GUIDE_MAX_CLUSTERS)));
  // The radius: twice the flux-weighted RMS distance from the centroid (1.4 times a uniform disc's radius), so that
  // a few dim photons sharing a bright patch's cell do not widen its cone; never less than a sixteenth of a cell (one
  // photon alone).
  const double cell = 2.0 / kGuideGridCells;
  std::vector<GuideCluster> clusters;
  for (const Region* r : order) {
    GuideCluster c{};
    glm::dvec3 normal = r->weighted_normal / r->weight;
    for (int a = 0; a < 3; ++a) {
      c.centre[a] = float(r->weighted_position[a]);
      c.flux[a] = float(r->flux[a]);
      c.normal[a] = float(normal[a]);
    }
    c.radius = float(std::max(2.0 * std::sqrt(r->square_distances / r->weight), cell / 16.0));
    clusters.push_back(c);
  }
  return clusters;
}

}  // namespace rcsplat
