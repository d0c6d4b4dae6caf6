// The classic lookup: every record whose Ward weight at P exceeds 1/a, found through the octree, in double.
#pragma once
#include <vector>

#include "cache/cache_math.h"
#include "cache/record_octree.h"

namespace rcsplat {

struct PixelGeometry {
  glm::vec3 p, n, ng;
  bool valid;
};

// Sum of w * E_k(P) and of w over the usable records at one pixel, in double.
struct Interpolation {
  glm::dvec3 weighted{0.0};
  double weight = 0.0;
  uint32_t count = 0;
};

inline Interpolation interpolate(const RecordOctree& octree, const std::vector<CacheRecord>& records, const PixelGeometry& g,
                          float accuracy) {
  Interpolation out;
  octree.for_each_reaching(glm::dvec3(g.p), [&](uint32_t k) {
    const CacheRecord& r = records[k];
    glm::vec3 pk = record_position(r), nk = record_normal(r);
    float w = ward_weight(g.p, g.n, pk, nk, r.radius);
    if (!record_usable(w, accuracy, g.p, g.n, pk, nk, r.radius)) return;
    out.weighted += double(w) * extrapolated_irradiance(r, glm::dvec3(g.p), glm::dvec3(g.n));
    out.weight += w;
    ++out.count;
  });
  return out;
}

}  // namespace rcsplat
