#include "cache/photon_map.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

#include "kernels/photon_grid.h"
#include "util/parallel.h"

namespace rcsplat {

float photon_patch_area(float radius) {
  return float(std::numbers::pi) * radius * radius / float(PHOTON_PATCHES_PER_DISC);
}

float photon_gather_radius(double surface_area, size_t photons, unsigned neighbours) {
  if (!(surface_area > 0.0) || !photons) return 0.0f;
  return float(std::sqrt(double(neighbours) * surface_area / (std::numbers::pi * double(photons))));
}

std::vector<PhotonHit> lit_landings(const std::vector<PhotonHit>& photons) {
  std::vector<PhotonHit> kept;
  kept.reserve(photons.size());
  for (const PhotonHit& p : photons)
    if (p.hit && (p.incident[0] > 0.0f || p.incident[1] > 0.0f || p.incident[2] > 0.0f)) kept.push_back(p);
  return kept;
}

namespace {

// Items in this many ranges are counted and scattered independently: a fixed number, so the work's split, and with
// it every bit of the result, is the same on any machine.
constexpr size_t kSortRanges = 64;

// items (anything with a position) sorted into a grid of cells one radius wide (and a hair more, so rounding never
// hides an item within the radius) by a counting sort, which keeps the order given within a bucket: the same items
// give the same grid. No radius (no surface to spread over): no items, so a lookup finds nothing.
// On all cores, as a two-digit stable radix sort of the bucket numbers: first by their high bits (at most 1024 bins;
// each of kSortRanges ranges of items counts its own and writes them in order), then each bin by the low bits, and
// finally the items gathered in that order. Each step is stable, so the result is the one-pass counting sort's, bit
// for bit (tests/photon_map_test.cpp).
template <class Item>
PhotonMapParams grid_params(const std::vector<Item>& items, float radius) {
  std::array<float, 3> lowest = {INFINITY, INFINITY, INFINITY};
  for (const Item& item : items)
    for (int a = 0; a < 3; ++a) lowest[a] = std::min(lowest[a], item.position[a]);
  return photon_grid_params(items.size(), lowest, radius);
}

template <class Item>
void sort_into_buckets(const std::vector<Item>& given, float radius, PhotonMapParams& params,
                       std::vector<Item>& sorted, std::vector<uint32_t>& bucket_starts) {
  const std::vector<Item> none;
  const std::vector<Item>& items = radius > 0.0f && std::isfinite(radius) ? given : none;
  params = grid_params(items, radius);
  const size_t count = items.size();
  std::vector<uint32_t> bucket(count);
  parallel_ranges(count, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      int c[3];
      for (int a = 0; a < 3; ++a) c[a] = photon_cell(items[i].position[a], params.grid_origin[a], params.cell_size);
      bucket[i] = photon_bucket(c[0], c[1], c[2], params.bucket_count);
    }
  });
  const unsigned bucket_bits = unsigned(std::countr_zero(params.bucket_count));
  const unsigned low_bits = bucket_bits > 10 ? bucket_bits - 10 : 0;
  const size_t bins = size_t(params.bucket_count) >> low_bits, range = (count + kSortRanges - 1) / kSortRanges;

  // High digit: each range's count per bin, then where each (bin, range) pair starts, bins first; the items' numbers
  // and buckets (not the items) move.
  std::vector<uint32_t> offsets(bins * kSortRanges, 0);
  parallel_for(kSortRanges, [&](size_t r) {
    for (size_t i = r * range; i < std::min(count, (r + 1) * range); ++i)
      ++offsets[(bucket[i] >> low_bits) * kSortRanges + r];
  }, 1);
  std::vector<uint32_t> bin_starts(bins + 1, 0);
  uint32_t running = 0;
  for (size_t b = 0; b < bins; ++b) {
    bin_starts[b] = running;
    for (size_t r = 0; r < kSortRanges; ++r) {
      const uint32_t n = offsets[b * kSortRanges + r];
      offsets[b * kSortRanges + r] = running;
      running += n;
    }
  }
  bin_starts[bins] = running;
  std::vector<std::pair<uint32_t, uint32_t>> by_bin(count);  // (bucket, item)
  parallel_for(kSortRanges, [&](size_t r) {
    for (size_t i = r * range; i < std::min(count, (r + 1) * range); ++i)
      by_bin[offsets[(bucket[i] >> low_bits) * kSortRanges + r]++] = {bucket[i], uint32_t(i)};
  }, 1);

  // Low digit, a bin at a time: a counting sort of its items into their buckets, whose starts it also fills.
  bucket_starts.assign(size_t(params.bucket_count) + 1, 0);
  std::vector<uint32_t> order(count);
  const size_t per_bin = size_t(1) << low_bits;
  parallel_for(bins, [&](size_t b) {
    std::vector<uint32_t> next(per_bin + 1, 0);
    for (uint32_t i = bin_starts[b]; i < bin_starts[b + 1]; ++i) ++next[(by_bin[i].first & (per_bin - 1)) + 1];
    next[0] = bin_starts[b];
    for (size_t k = 0; k < per_bin; ++k) next[k + 1] += next[k];
    std::copy(next.begin(), next.end() - 1, bucket_starts.begin() + ptrdiff_t(b * per_bin));  // this bin's own
    for (uint32_t i = bin_starts[b]; i < bin_starts[b + 1]; ++i)
      order[next[by_bin[i].first & (per_bin - 1)]++] = by_bin[i].second;
  }, 4);
  sorted.resize(count);
  parallel_ranges(count, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) sorted[k] = items[order[k]];
  });
  bucket_starts[params.bucket_count] = running;
}

}  // namespace

PhotonMapParams photon_grid_params(size_t items, const std::array<float, 3>& lowest, float radius) {
  PhotonMapParams params{};
  const size_t count = radius > 0.0f && std::isfinite(radius) ? items : 0;
  params.radius = radius;
  params.cell_size = radius * 1.001f;
  params.bucket_count = uint32_t(std::bit_ceil(std::max<size_t>(2 * count, 2)));
  params.photon_count = uint32_t(count);
  for (int a = 0; a < 3; ++a) params.grid_origin[a] = count == 0 ? 0.0f : lowest[a] - params.cell_size;
  return params;
}

PhotonMapParams photon_grid_params(const std::vector<PhotonHit>& photons, float radius) {
  return grid_params(photons, radius);
}

PhotonMapParams photon_grid_params(const std::vector<SurfacePatch>& patches, float radius) {
  return grid_params(patches, radius);
}

PhotonGrid sort_into_grid(const std::vector<PhotonHit>& photons, float radius) {
  PhotonGrid grid;
  sort_into_buckets(photons, radius, grid.params, grid.photons, grid.bucket_starts);
  return grid;
}

std::vector<uint32_t> cell_order(const PhotonGrid& grid) {
  const size_t count = grid.photons.size();
  // 21 bits per axis, counted from the lowest cell: a scene more than two million cells wide only loses some order.
  auto spread = [](uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  std::vector<std::array<int, 3>> cells(count);
  std::array<int, 3> lowest;
  lowest.fill(std::numeric_limits<int>::max());
  for (size_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) {
      cells[i][a] = photon_cell(grid.photons[i].position[a], grid.params.grid_origin[a], grid.params.cell_size);
      lowest[a] = std::min(lowest[a], cells[i][a]);
    }
  std::vector<uint64_t> code(count, 0);
  for (size_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) code[i] |= spread(uint64_t(int64_t(cells[i][a]) - lowest[a])) << a;
  std::vector<uint32_t> order(count);
  for (size_t i = 0; i < count; ++i) order[i] = uint32_t(i);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
  return order;
}

PatchGrid sort_into_grid(const std::vector<SurfacePatch>& patches, float radius) {
  PatchGrid grid;
  sort_into_buckets(patches, radius, grid.params, grid.patches, grid.bucket_starts);
  return grid;
}

namespace {

// One triangle of surface_patches: its corner, edges, unit normal, and the n x n cut into sub-triangles of about the
// patch area (cuts 0: a degenerate triangle, no patch).
struct PatchedTriangle {
  glm::dvec3 a, e1, e2, n;
  int cuts = 0;
  float area = 0.0f;  // each sub-triangle's

  PatchedTriangle(const glm::vec3* corners, float patch_area) {
    constexpr double kMaxCuts = 256.0;  // a huge triangle gets patches larger than asked: still its exact area
    a = glm::dvec3(corners[0]);
    e1 = glm::dvec3(corners[1]) - a;
    e2 = glm::dvec3(corners[2]) - a;
    const glm::dvec3 c = glm::cross(e1, e2);
    const double twice_area = glm::length(c);
    if (!(twice_area > 0.0) || !std::isfinite(twice_area)) return;
    n = c / twice_area;
    cuts = int(std::clamp(std::ceil(std::sqrt(0.5 * twice_area / double(patch_area))), 1.0, kMaxCuts));
    area = float(0.5 * twice_area / double(cuts * cuts));
  }
  size_t patch_count() const { return 2 * size_t(cuts) * size_t(cuts); }  // cuts^2 sub-triangles, two sides each

  // Sub-triangle (i, j) of the n x n cut: its centroid in units of the edges over n; the upward ones at
  // (i + 1/3, j + 1/3), the downward ones between them at (i + 2/3, j + 2/3).
  void write_patches(SurfacePatch* out) const {
    auto add = [&](double u, double v) {
      const glm::dvec3 x = a + (u / cuts) * e1 + (v / cuts) * e2;
      for (double side : {1.0, -1.0}) {
        SurfacePatch p{};
        for (int k = 0; k < 3; ++k) p.position[k] = float(x[k]), p.normal[k] = float(side * n[k]);
        p.area = area;
        *out++ = p;
      }
    };
    for (int i = 0; i < cuts; ++i)
      for (int j = 0; i + j < cuts; ++j) {
        add(i + 1.0 / 3.0, j + 1.0 / 3.0);
        if (i + j + 1 < cuts) add(i + 2.0 / 3.0, j + 2.0 / 3.0);
      }
  }
};

}  // namespace

std::vector<SurfacePatch> surface_patches(const std::vector<glm::vec3>& positions, float patch_area) {
  if (!(patch_area > 0.0f) || !std::isfinite(patch_area)) return {};
  // On all cores: each triangle's patch count, where its patches start, then each triangle writes its own.
  const size_t triangles = positions.size() / 3;
  std::vector<size_t> first(triangles + 1, 0);
  parallel_ranges(triangles, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) first[t + 1] = PatchedTriangle(&positions[3 * t], patch_area).patch_count();
  });
  for (size_t t = 0; t < triangles; ++t) first[t + 1] += first[t];
  std::vector<SurfacePatch> patches(first[triangles]);
  parallel_ranges(triangles, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t)
      PatchedTriangle(&positions[3 * t], patch_area).write_patches(&patches[first[t]]);
  }, 1024);
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
    grids.patches = sort_into_grid(surface_patches(triangles, photon_patch_area(radius)), radius);
  }
  return grids;
}

}  // namespace rcsplat
