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
    if (p.hit && (p.flux[0] > 0.0f || p.flux[1] > 0.0f || p.flux[2] > 0.0f)) kept.push_back(p);
  return kept;
}

PhotonGrid sort_into_grid(const std::vector<PhotonHit>& given, float radius) {
  // No radius (no surface to spread over): no photon can be found, so keep none (a lookup then returns no light).
  const std::vector<PhotonHit> none;
  const std::vector<PhotonHit>& photons = radius > 0.0f && std::isfinite(radius) ? given : none;
  PhotonGrid grid;
  PhotonMapParams& params = grid.params;
  params.radius = radius;
  params.cell_size = radius * 1.001f;
  params.bucket_count = uint32_t(std::bit_ceil(std::max<size_t>(2 * photons.size(), 2)));
  params.photon_count = uint32_t(photons.size());
  float lo[3] = {INFINITY, INFINITY, INFINITY};
  for (const PhotonHit& p : photons)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p.position[a]);
  for (int a = 0; a < 3; ++a) params.grid_origin[a] = photons.empty() ? 0.0f : lo[a] - params.cell_size;

  // A counting sort by bucket keeps the photons' order within a bucket: the same photons give the same grid.
  std::vector<uint32_t> bucket(photons.size());
  grid.bucket_starts.assign(size_t(params.bucket_count) + 1, 0);
  for (size_t i = 0; i < photons.size(); ++i) {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = photon_cell(photons[i].position[a], params.grid_origin[a], params.cell_size);
    bucket[i] = photon_bucket(c[0], c[1], c[2], params.bucket_count);
    ++grid.bucket_starts[bucket[i] + 1];
  }
  for (size_t h = 0; h < params.bucket_count; ++h) grid.bucket_starts[h + 1] += grid.bucket_starts[h];
  std::vector<uint32_t> next(grid.bucket_starts.begin(), grid.bucket_starts.end() - 1);
  grid.photons.resize(photons.size());
  for (size_t i = 0; i < photons.size(); ++i) grid.photons[next[bucket[i]]++] = photons[i];
  return grid;
}

PhotonMapGrids build_photon_map(const std::vector<PhotonHit>& kept, double surface_area, unsigned neighbours,
                                unsigned lookup_stride) {
  float radius = photon_gather_radius(surface_area, kept.size(), neighbours);
  std::vector<PhotonHit> sparse;
  for (size_t i = 0; i < kept.size(); i += std::max(lookup_stride, 1u)) sparse.push_back(kept[i]);
  return {sort_into_grid(kept, radius), sort_into_grid(sparse, radius)};
}

}  // namespace rcsplat
