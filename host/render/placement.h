// Record placement, coarse to fine (docs/ALGORITHM.md section 7), written once for both cache methods. What differs
// between them is behind RecordIndex: how a grid's uncovered pixels are found and how radii are clamped against
// neighbours (the device's coverage and clamping kernels, or the host's octree). Records are computed by the one
// record pass for both, so the two methods place the same records at the same pixels.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "cache/cache_settings.h"
#include "passes/gbuffer_pass.h"
#include "passes/record_pass.h"
#include "render/frame.h"

namespace rcsplat {

class RecordIndex {
 public:
  virtual ~RecordIndex() = default;
  // Finds the pixels on the grid of this spacing that see geometry, hold no record, and that no usable record among
  // 0 .. record_count - 1 reaches (Ward weight above 1/a, not in front); returns their count and lists them in
  // candidates(), a device array of pixel indices. Records 0 .. unchanged_before - 1 kept their radii since the last
  // call at this spacing.
  virtual uint32_t find_uncovered(RecordPass& records, uint32_t record_count, int spacing,
                                  uint32_t unchanged_before) = 0;
  virtual const cl::Buffer& candidates() const = 0;
  // Records first .. first + count - 1 have been computed and now sit on their pixels.
  virtual void add_records(RecordPass& records, uint32_t first, uint32_t count) = 0;
  // R_i <= R_j + |P_i - P_j| over records 0 .. count - 1, for the pairs with a record first_new or later (Křivánek et
  // al. 2006); older records keep their radii unless clamp_older.
  virtual void clamp_neighbours(RecordPass& records, uint32_t count, uint32_t first_new, bool clamp_older) = 0;
};

// At spacing 1 every candidate becomes a record and covers itself, but neighbour clamping can shrink an older record
// enough to uncover a pixel, so up to this many rounds run there; after the first, only new records are clamped (a
// symmetric clamp would uncover pixels again, cascading along corners for dozens of rounds).
constexpr int kRoundsAtFinestSpacing = 5;

// Called after each batch of records first .. first + count - 1 is computed with these hemisphere parameters (radiance
// caching projects the batch's strata there).
using RecordBatchHook = std::function<void(uint32_t first, uint32_t count, const HemisphereParams& hemisphere)>;

// Places records level after level: find the grid's uncovered pixels, compute them as one batch, let them cover,
// clamp radii against neighbours. Fills the statistics' per-level counts and times (the hook's time counts as the
// records'); returns the number of records. Records 0 .. first_record - 1 are already there and seated (records kept
// from earlier frames: render/kept_records.h): they count in the coverage and the total.
uint32_t place_records(RecordIndex& index, RecordPass& records, const GBufferView& gbuffer, const CacheSettings& cache,
                       unsigned seed, RecordStats& stats, const RecordBatchHook& after_batch = {},
                       const char* progress_label = "irradiance cache", uint32_t first_record = 0);

// Counts the records whose reach sits at a screen-space clamp, for the summary.
void count_clamped_radii(const std::vector<CacheRecord>& records, const CacheSettings& cache, RecordStats& stats);

}  // namespace rcsplat
