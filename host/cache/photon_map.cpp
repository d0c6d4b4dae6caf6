#include "cache/photon_map.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "kernels/photon_grid.h"

namespace rcsplat {

float photon_gather_radius(double surface_area, size_t photons, unsigned neighbours) {
  if (!(surface_area > 0.0) || !photons) return 0.0f;
  return float(std::sqrt(double(neighbours) * surface_area / (std::numbers::pi * double(photons))));
}

std::vector<PhotonHit> lit_landings(const std::vector<PhotonHit>& photons) {
  std::vector<PhotonHit> kept;
  for (const PhotonHit& p : photons)
    if (p.hit && (p.incident[0] > 0.0f || p.incident[1] > 0.0f || p.incident[2] > 0.0f)) kept.push_back(p);
  return kept;
}

namespace {

// items (anything with a position) sorted into a grid of cells one radius wide (and a hair more, so rounding never
// hides an item within the radius) by a counting sort, which keeps the order given within a bucket: the same items
// give the same grid. No radius (no surface to spread over): no items, so a lookup finds nothing.
template <class Item>
void sort_into_buckets(const std::vector<Item>& given, float radius, PhotonMapParams& params,
                       std::vector<Item>& sorted, std::vector<uint32_t>& bucket_starts) {
  const std::vector<Item> none;
  const std::vector<Item>& items = radius > 0.0f && std::isfinite(radius) ? given : none;
  params.radius = radius;
  params.cell_size = radius * 1.001f;
  params.bucket_count = uint32_t(std::bit_ceil(std::max<size_t>(2 * items.size(), 2)));
  params.photon_count = uint32_t(items.size());
  float lo[3] = {INFINITY, INFINITY, INFINITY};
  for (const Item& p : items)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p.position[a]);
  for (int a = 0; a < 3; ++a) params.grid_origin[a] = items.empty() ? 0.0f : lo[a] - params.cell_size;
  std::vector<uint32_t> bucket(items.size());
  bucket_starts.assign(size_t(params.bucket_count) + 1, 0);
  for (size_t i = 0; i < items.size(); ++i) {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = photon_cell(items[i].position[a], params.grid_origin[a], params.cell_size);
    bucket[i] = photon_bucket(c[0], c[1], c[2], params.bucket_count);
    ++bucket_starts[bucket[i] + 1];
  }
  for (size_t h = 0; h < params.bucket_count; ++h) bucket_starts[h + 1] += bucket_starts[h];
  std::vector<uint32_t> next(bucket_starts.begin(), bucket_starts.end() - 1);
  sorted.resize(items.size());
  for (size_t i = 0; i < items.size(); ++i) sorted[next[bucket[i]]++] = items[i];
}

}  // namespace

PhotonGrid sort_into_grid(const std::vector<PhotonHit>& photons, float radius) {
  PhotonGrid grid;
  sort_into_buckets(photons, radius, grid.params, grid.photons, grid.bucket_starts);
  return grid;
}

PatchGrid sort_into_grid(const std::vector<SurfacePatch>& patches, float radius) {
  PatchGrid grid;
  sort_into_buckets(patches, radius, grid.params, grid.patches, grid.bucket_starts);
  return grid;
}

std::vector<SurfacePatch> surface_patches(const std::vector<glm::vec3>& positions, float patch_area) {
  std::vector<SurfacePatch> patches;
  if (!(patch_area > 0.0f) || !std::isfinite(patch_area)) return patches;
  constexpr double kMaxCuts = 256.0;  // a huge triangle gets patches larger than asked: still its exact area
  for (size_t t = 0; t + 2 < positions.size(); t += 3) {
    const glm::dvec3 a(positions[t]), e1 = glm::dvec3(positions[t + 1]) - a, e2 = glm::dvec3(positions[t + 2]) - a;
    const glm::dvec3 c = glm::cross(e1, e2);
    const double twice_area = glm::length(c);
    if (!(twice_area > 0.0) || !std::isfinite(twice_area)) continue;
    const glm::dvec3 n = c / twice_area;
    const int cuts = int(std::clamp(std::ceil(std::sqrt(0.5 * twice_area / double(patch_area))), 1.0, kMaxCuts));
    const float area = float(0.5 * twice_area / double(cuts * cuts));
    // Sub-triangle (i, j) of the n x n cut: its centroid in units of the edges over n; the upward ones at
    // (i + 1/3, j + 1/3), the downward ones between them at (i + 2/3, j + 2/3).
    auto add = [&](double u, double v) {
      const glm::dvec3 x = a + (u / cuts) * e1 + (v / cuts) * e2;
      for (double side : {1.0, -1.0}) {
        SurfacePatch p{};
        for (int k = 0; k < 3; ++k) p.position[k] = float(x[k]), p.normal[k] = float(side * n[k]);
        p.area = area;
        patches.push_back(p);
      }
    };
    for (int i = 0; i < cuts; ++i)
      for (int j = 0; i + j < cuts; ++j) {
        add(i + 1.0 / 3.0, j + 1.0 / 3.0);
        if (i + j + 1 < cuts) add(i + 2.0 / 3.0, j + 2.0 / 3.0);
      }
  }
  return patches;
}

PhotonMapGrids build_photon_map(const std::vector<PhotonHit>& kept, double surface_area, unsigned neighbours,
                                unsigned lookup_stride, const std::vector<glm::vec3>& triangles) {
  float radius = photon_gather_radius(surface_area, kept.size(), neighbours);
  std::vector<PhotonHit> sparse;
  for (size_t i = 0; i < kept.size(); i += std::max(lookup_stride, 1u)) sparse.push_back(kept[i]);
  PhotonMapGrids grids;
  grids.all = sort_into_grid(kept, radius);
  grids.lookup = sort_into_grid(sparse, radius);
  if (!kept.empty()) {
    const float patch_area = float(std::numbers::pi) * radius * radius / float(PHOTON_PATCHES_PER_DISC);
    grids.patches = sort_into_grid(surface_patches(triangles, patch_area), radius);
  }
  return grids;
}

}  // namespace rcsplat
