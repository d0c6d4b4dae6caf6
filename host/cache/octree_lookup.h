// The classic lookup: every record whose Ward weight at P exceeds 1/a, found through the octree, with the cache's
// shared math (kernels/cache_math.h), summed in double.
#pragma once
#include <vector>

#include "cache/record_octree.h"
#include "kernels/cache_math.h"

namespace rcsplat {

inline glm::vec3 record_position(const CacheRecord& r) { return rc_load3(0, r.position); }
inline glm::vec3 record_normal(const CacheRecord& r) { return rc_load3(0, r.normal); }
inline glm::vec3 record_irradiance(const CacheRecord& r) { return rc_load3(0, r.irradiance); }

struct PixelGeometry {
  glm::vec3 p, n;
  bool valid;  // the pixel sees geometry
};

inline PixelGeometry pixel_geometry(const GBufferSample& g) {
  return {rc_load3(0, g.position), rc_load3(0, g.normal), g.triangle >= 0};
}

// Sum of w * E_k(P) and of w over the usable records at one pixel, in double.
struct Interpolation {
  glm::dvec3 weighted{0.0};
  double weight = 0.0;
  uint32_t count = 0;
};

// record_reaches with the record's horizon frame (the device kernels compute it once per record).
inline bool record_reaches_pixel(const CacheRecord& r, float w, float accuracy, const PixelGeometry& g,
                                 const glm::vec3& pk, const glm::vec3& nk) {
  glm::vec3 t, b;
  tangent_frame(nk, &t, &b);
  return record_reaches(&r, t, b, w, accuracy, g.p, g.n, pk, nk, r.radius);
}

inline Interpolation interpolate(const RecordOctree& octree, const std::vector<CacheRecord>& records,
                                 const PixelGeometry& g, float accuracy) {
  Interpolation out;
  octree.for_each_reaching(glm::dvec3(g.p), [&](uint32_t k) {
    const CacheRecord& r = records[k];
    glm::vec3 pk = record_position(r), nk = record_normal(r);
    float w = ward_weight(g.p, g.n, pk, nk, r.radius);
    if (!record_reaches_pixel(r, w, accuracy, g, pk, nk)) return;
    out.weighted += double(w) * glm::dvec3(extrapolated_irradiance(&r, g.p, g.n));
    out.weight += w;
    ++out.count;
  });
  return out;
}

// Whether some record is usable at the pixel: the placement's coverage test. Not interpolate(...).weight > 0: this
// stops evaluating weights at the first usable record (measured: sharing interpolate's loop made Sponza's octree
// placement 45% slower).
inline bool covered(const RecordOctree& octree, const std::vector<CacheRecord>& records, const PixelGeometry& g,
                    float accuracy) {
  bool any = false;
  octree.for_each_reaching(glm::dvec3(g.p), [&](uint32_t k) {
    const CacheRecord& r = records[k];
    glm::vec3 pk = record_position(r), nk = record_normal(r);
    any = any || record_reaches_pixel(r, ward_weight(g.p, g.n, pk, nk, r.radius), accuracy, g, pk, nk);
  });
  return any;
}

}  // namespace rcsplat
