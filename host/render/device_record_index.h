// Placement's coverage and clamping on the device (kernels/placement.cl), for the splat's irradiance records and
// its radiance records alike.
#pragma once
#include <vector>

#include "passes/placement_pass.h"
#include "render/placement.h"

namespace rcsplat {

class DeviceRecordIndex final : public RecordIndex {
 public:
  DeviceRecordIndex(GpuContext& gpu, const GBufferView& gbuffer, const CacheSettings& cache)
      : pass_(gpu, gbuffer), accuracy_(cache.accuracy), min_radius_pixels_(min_radius_pixels(cache)) {}
  // A new frame through an index kept across frames: no record placed yet.
  void begin(const GBufferView& gbuffer, const CacheSettings& cache) {
    pass_.begin(gbuffer);
    accuracy_ = cache.accuracy;
    min_radius_pixels_ = min_radius_pixels(cache);
  }

  uint32_t find_uncovered(RecordPass& records, uint32_t record_count, int spacing, uint32_t unchanged_before) override {
    return pass_.find_uncovered(records.records(), record_count, accuracy_, spacing, unchanged_before);
  }
  const cl::Buffer& candidates() const override { return pass_.candidates(); }
  void add_records(RecordPass& records, uint32_t first, uint32_t count) override {
    pass_.mark(records.records(), first, count);
  }
  void clamp_neighbours(RecordPass& records, uint32_t count, uint32_t first_new, bool clamp_older) override {
    pass_.clamp_neighbours(records.records(), count, first_new, clamp_older, min_radius_pixels_);
  }
  // Records 0 .. count - 1 of `records`, kept from earlier frames, fitted to this view and seated where it sees them
  // (PlacementPass::fit_kept), before placement adds any.
  void seat_kept(RecordPass& records, uint32_t count, const CacheSettings& cache) {
    pass_.fit_kept(records.records(), count, min_radius_pixels(cache), max_radius_pixels(cache),
                   !(cache.hessian_error > 0.0f));
    pass_.mark(records.records(), 0, count);
  }
  std::vector<int32_t> record_at_pixel() { return pass_.record_at_pixel(); }
  const cl::Buffer& record_at_pixel_buffer() const { return pass_.record_at_pixel_buffer(); }

 private:
  PlacementPass pass_;
  float accuracy_, min_radius_pixels_;
};

}  // namespace rcsplat
