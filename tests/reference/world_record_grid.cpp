#include "reference/world_record_grid.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <utility>

#include "kernels/cache_math.h"
#include "kernels/photon_grid.h"
#include "kernels/world_record_cells.h"

namespace rcsplat {

WorldRecordGrid build_world_record_grid(const std::vector<CacheRecord>& records, float accuracy) {
  WorldRecordGrid grid;
  grid.params.accuracy = accuracy;
  float largest = 0.0f;  // as the splat's max_record_irradiance (kernels/splat.cl)
  for (const CacheRecord& r : records)
    largest = std::max({largest, r.irradiance[0], r.irradiance[1], r.irradiance[2]});
  grid.params.irradiance_scale = fixed_point_irradiance_scale(largest, accuracy);
  grid.params.bucket_count = 1;
  grid.bucket_starts = {0, 0};
  std::vector<uint32_t> kept;
  std::vector<float> diameters;
  float lo[3] = {INFINITY, INFINITY, INFINITY};
  for (uint32_t i = 0; i < records.size(); ++i) {
    const CacheRecord& r = records[i];
    const float reach = accuracy * r.radius;
    bool finite = std::isfinite(reach) && reach > 0.0f;
    for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(r.position[a]);
    if (!finite) continue;
    kept.push_back(i);
    diameters.push_back(2.0f * reach);
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], r.position[a] - reach);
  }
  if (kept.empty()) return grid;
  std::vector<float> sorted = diameters;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const float median = sorted[sorted.size() / 2], widest = *std::max_element(diameters.begin(), diameters.end());
  const float cell = std::max(median, widest / 8.0f);
  WorldRecordParams& params = grid.params;
  params.cell_size = cell;
  for (int a = 0; a < 3; ++a) params.grid_origin[a] = lo[a] - cell;

  // Each cell a reach sphere meets (not only its bounding cube), with the record.
  std::vector<std::array<int, 3>> cells;
  std::vector<uint32_t> owners;
  const float* o = params.grid_origin;
  for (uint32_t i : kept) {
    const CacheRecord& r = records[i];
    const float reach = accuracy * r.radius;
    int c0[3], c1[3];
    for (int a = 0; a < 3; ++a) reach_cell_span(r.position[a], reach, o[a], cell, &c0[a], &c1[a]);
    for (int z = c0[2]; z <= c1[2]; ++z)
      for (int y = c0[1]; y <= c1[1]; ++y)
        for (int x = c0[0]; x <= c1[0]; ++x)
          if (reach_meets_cell(r.position[0], r.position[1], r.position[2], reach, o[0], o[1], o[2], cell, x, y, z)) {
            cells.push_back({x, y, z});
            owners.push_back(i);
          }
  }
  params.bucket_count = uint32_t(std::bit_ceil(std::max<size_t>(2 * cells.size(), 2)));
  std::vector<std::pair<uint32_t, uint32_t>> entries(cells.size());
  for (size_t k = 0; k < cells.size(); ++k)
    entries[k] = {photon_bucket(cells[k][0], cells[k][1], cells[k][2], params.bucket_count), owners[k]};
  // Two cells may hash to one bucket: a record listed there once.
  std::sort(entries.begin(), entries.end());
  entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
  grid.bucket_starts.assign(size_t(params.bucket_count) + 1, 0);
  for (const auto& [bucket, record] : entries) ++grid.bucket_starts[bucket + 1];
  for (size_t b = 0; b < params.bucket_count; ++b) grid.bucket_starts[b + 1] += grid.bucket_starts[b];
  grid.record_lists.reserve(entries.size());
  for (const auto& [bucket, record] : entries) grid.record_lists.push_back(record);
  params.record_count = uint32_t(records.size());
  return grid;
}

}  // namespace rcsplat
