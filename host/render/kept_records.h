// Irradiance records kept across the frames of a camera path (issue 42): a record is a point in the world with its
// light, valid for any view that sees it, so a walkthrough's frame splats the records earlier frames placed and places
// new ones only where none reaches (docs/ALGORITHM.md section 11).
//
// What stays and what each frame redoes:
// - A record is kept as it was when its frame finished placing it: position, irradiance, gradients and its radius
//   after that frame's clamps (screen and neighbours). Kept records never change; a frame works on a copy.
// - Each frame takes the kept records whose reach sphere meets its view frustum, in the order they were kept, and
//   fits them to its view on the device (kernels/placement.cl fit_kept_records): the radius goes back into the
//   [min, max] reach in this view's pixel footprints where it has left them by more than 0.1%, so a record that was
//   far away when placed does not cover half of the screen up close, nor shrink below a few pixels far away; and each
//   record sits on the pixel it projects to where the G-buffer sees it, so that no second record is placed there.
//   Placement then runs as for a fresh frame, its coverage counting the kept records.
// - Records never reached by a frame's frustum for the longest are evicted when more than `capacity` are kept.
// The light the records read (photon map, light guide, caustic map) is kept by the Renderer already
// (ViewIndependentLight), so a record placed at frame 90 sees the same photons as one placed at frame 0.
#pragma once
#include <cstdint>
#include <vector>

#include "cache/cache_settings.h"
#include "kernels/shared_types.h"
#include "render/frame.h"
#include "render/settings.h"

namespace rcsplat {

// What kept records were computed with: a change in any of it drops them.
struct KeptRecordsKey {
  CacheSettings cache;
  unsigned seed = 0, bounces = 0, photon_paths = 0, photon_neighbours = 0, caustic_photons = 0, sub_pixel_side = 1;
  BounceMethod bounce_method = BounceMethod::automatic;
  float short_ray_paths = 0.0f, photon_min_support = 0.0f;
  bool operator==(const KeptRecordsKey&) const = default;
};
KeptRecordsKey kept_records_key(const RenderSettings& frame_settings);

class KeptRecords {
 public:
  explicit KeptRecords(size_t capacity) : capacity_(capacity) {}

  // Starts a frame: drops every record when the key changed.
  void begin_frame(const KeptRecordsKey& key);
  // The kept records whose reach (a times the radius, or the view's minimum reach if larger) may meet the view of
  // `camera` (device coordinates), in the order they were kept; they count as used by this frame.
  std::vector<CacheRecord> for_view(const CameraParams& camera, const CacheSettings& cache);
  // Keeps the records this frame placed (device coordinates), then evicts the least recently used past the capacity.
  void add(const CacheRecord* records, size_t count);

  const KeptRecordsStats& stats() const { return stats_; }
  size_t size() const { return records_.size(); }
  void set_capacity(size_t capacity) { capacity_ = capacity; }

  // For cache files (render/cache_file.h): what is kept, the frame that last used each record, the frames begun.
  const std::vector<CacheRecord>& records() const { return records_; }
  const std::vector<uint64_t>& last_used() const { return last_used_; }
  uint64_t frames_begun() const { return frame_; }
  // Replaces what is kept with a cache file's records, computed with these settings.
  void restore(const KeptRecordsKey& key, std::vector<CacheRecord> records, std::vector<uint64_t> last_used,
               uint64_t frames_begun);

 private:
  size_t capacity_;
  bool has_key_ = false;
  KeptRecordsKey key_;
  uint64_t frame_ = 0;
  std::vector<CacheRecord> records_;
  std::vector<uint64_t> last_used_;  // the last frame whose view took each record
  KeptRecordsStats stats_;
};

}  // namespace rcsplat
