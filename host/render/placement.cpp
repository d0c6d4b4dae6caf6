#include "render/placement.h"

#include <algorithm>
#include <cmath>

#include "kernels/cache_math.h"
#include "render/timing.h"
#include "util/log.h"

namespace rcsplat {
namespace {

void count_placed(RecordStats& st, int spacing, uint32_t records) {
  if (!st.levels.empty() && st.levels.back().spacing_pixels == spacing) st.levels.back().records += records;
  else st.levels.push_back({spacing, records});
}

}  // namespace

uint32_t place_records(RecordIndex& index, RecordPass& records, const GBufferView& gbuffer, const CacheSettings& cache,
                       unsigned seed, RecordStats& st, const RecordBatchHook& after_batch, const char* progress_label,
                       uint32_t first_record) {
  int coarsest = coarsest_placement_spacing(cache);
  Progress progress(progress_label, size_t(std::log2(coarsest)) + 1);
  uint32_t total = first_record;
  const int finest = std::min(cache.finest_spacing_pixels, coarsest);
  // Radiance records project each batch's strata onto HSH (after_batch), which needs one hemisphere per batch.
  const bool adaptive = cache.adaptive_error > 0.0f && !after_batch;
  if (cache.adaptive_error > 0.0f && after_batch)
    log_warning("--adaptive-rays: radiance records keep all their strata (their HSH projection takes one hemisphere "
                "per batch)");
  for (int spacing = coarsest, level = 0; spacing >= finest; spacing /= 2, ++level) {
    uint32_t unchanged = 0;  // in the extra rounds older records keep their radii: only new ones add coverage
    for (int round = 0; round < (spacing == finest ? kRoundsAtFinestSpacing : 1); ++round) {
      uint32_t count = 0;
      {
        StageTimer timing(st.placement_s);
        count = index.find_uncovered(records, total, spacing, unchanged);
      }
      if (!count) break;
      {
        StageTimer timing(st.records_s);
        HemisphereParams hemisphere = hemisphere_params(cache, seed, spacing);
        HemisphereParams coarse = hemisphere;
        coarse.theta_strata /= 2;
        coarse.phi_strata /= 2;
        if (adaptive && coarse.theta_strata > 0 && coarse.phi_strata > 0)
          st.adaptive_records += records.compute_adaptive(gbuffer, index.candidates(), count, total, coarse,
                                                          hemisphere, cache.adaptive_error);
        else
          records.compute(gbuffer, index.candidates(), count, total, hemisphere);
        if (after_batch) after_batch(total, count, hemisphere);
      }
      {
        StageTimer timing(st.placement_s);
        index.add_records(records, total, count);
        total += count;
        index.clamp_neighbours(records, total, total - count, round == 0);
        unchanged = round == 0 ? 0 : total - count;
      }
      count_placed(st, spacing, count);
    }
    progress.update(size_t(level + 1));
  }
  progress.finish();
  st.records = total;
  st.rays = records.rays_cast();
  return total;
}

void count_clamped_radii(const std::vector<CacheRecord>& records, const CacheSettings& cache, RecordStats& st) {
  for (const CacheRecord& r : records) {
    const int side =
        reach_clamp_side(cache.accuracy, r.radius, r.pixel_size, cache.min_reach_pixels, cache.max_reach_pixels);
    if (side < 0) ++st.at_min_radius;
    else if (side > 0) ++st.at_max_radius;
  }
}

}  // namespace rcsplat
