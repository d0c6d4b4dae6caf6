// Irradiance and radiance records kept across the frames of a camera path (issue 42): a record is a point in the world with its
// light, valid for any view that sees it, so a walkthrough's frame splats the records earlier frames placed and places
// new ones only where none reaches (docs/ALGORITHM.md section 11).
//
// What stays and what each frame redoes:
// - A record is kept as it was when its frame finished placing it: position, irradiance, gradients and its radius
//   after that frame's clamps (screen and neighbours). Kept records never change; a frame works on a copy.
// - Each frame takes the kept records whose reach sphere meets its view frustum, in the order they were kept, and
//   fits them to its view on the device (kernels/placement.cl fit_kept_records): the radius goes back into the
//   [min, max] reach in this view's pixel footprints where it has left them by more than 0.1%, so a record that was
//   far away when placed does not cover half of the screen up close, nor shrink below a few pixels far away; a radius
//   an earlier view's minimum enlarged shrinks back toward the record's harmonic distance; and each record sits on
//   the pixel it projects to where the G-buffer sees it, so that no second record is placed there.
//   Placement then runs as for a fresh frame, its coverage counting the kept records.
// - Records never reached by a frame's frustum for the longest are evicted when more than `capacity` are kept.
// The light the records read (photon map, light guide, caustic map) is kept by the Renderer already
// (ViewIndependentLight), so a record placed at frame 90 sees the same photons as one placed at frame 0; the photons
// and clusters it was made from are kept beside the records too (KeptLight), for cache files.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
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
  unsigned hsh_order = 0;  // the radiance records' coefficients
  BounceMethod bounce_method = BounceMethod::automatic;
  float short_ray_paths = 0.0f, photon_min_support = 0.0f;
  bool operator==(const KeptRecordsKey&) const = default;
};
KeptRecordsKey kept_records_key(const RenderSettings& frame_settings);

// One move of a moving part (device coordinates): the box it filled before and after, joined, and how far any of its
// points moved (infinite: unknown). A small part (a door) also lists its triangles before and after the move, three
// corners each, so that the beside rule measures the distance to the part itself rather than to its box, which for a
// turned thin part takes in the room around it; empty: the box alone.
struct SweptBox {
  glm::vec3 lo, hi;
  float displacement = INFINITY;
  std::vector<glm::vec3> triangles;
};

// A bound on how much of a record's light one move may change, as a fraction of it (docs/ALGORITHM.md section 14).
// Seen from the record, the part fills at most its bounding sphere (radius r, distance d, angular radius a, at angle
// theta from the normal), a share sin^2(a) cos(max(theta - a, 0)) of the cosine-weighted hemisphere (0 below the
// horizon). A move by delta shifts the sphere's outline by at most delta / d, and two discs of angular radius a that
// far apart differ by about 4 a (delta / d) of the sphere: a share of at most (4 / pi)(r / d)(delta / d) cos(...).
// The bound is the smaller of the two. The light seen there before and after differs by
// the scene's contrast, which this leaves to the tolerance. A record whose sphere of validity (radius R) reaches the
// part's box counts 1: it stands on, under or beside it; so does one inside the sphere around the box.
double moved_record_change(const CacheRecord& record, const SweptBox& swept);
// Whether the record's sphere of validity reaches the move's box (moved_record_change counts 1); where the move
// lists its triangles, whether the sphere, grown by the displacement, reaches one of them before or after the move
// (any point of the part in between lies within the displacement of where it was before).
bool record_beside_move(const CacheRecord& record, const SweptBox& swept);
// The distance from p to the triangle (a, b, c), degenerate ones too.
double distance_to_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
// The same over several moves at once: beside any of them, and the sum of their bounds added to `before` (the
// record's change since it was made, summed in the moves' order).
bool record_beside_any(const CacheRecord& record, const std::vector<SweptBox>& moves);
double moved_record_change(const CacheRecord& record, const std::vector<SweptBox>& moves, double before = 0.0);

// A record's light at a later time (temporal windows, docs/ALGORITHM.md section 15): computed at the pixel it was
// computed at, with the scene posed at that time. Its position, normal and radius stay the record's.
struct RecordLightAhead {
  float irradiance[3];
  float grad_translation[9];
  float grad_rotation[9];
};
RecordLightAhead light_of(const CacheRecord& record);
// The record with its light a share s (0 .. 1) of the way from its own to `ahead`, each term linearly.
CacheRecord interpolated(const CacheRecord& record, const RecordLightAhead& ahead, double s);

// Records of one kind (irradiance or radiance) kept across frames. A radiance record carries its HSH coefficients
// beside it (`payload` floats a record, kernels/hsh_records.cl's layout), kept, taken and evicted with it.
class KeptRecords {
 public:
  explicit KeptRecords(size_t capacity) : capacity_(capacity) {}

  // Starts a frame: drops every record when the key changed, and then says so.
  bool begin_frame(const KeptRecordsKey& key);
  // The kept records whose reach (a times the radius, or the view's minimum reach if larger) may meet the view of
  // `camera` (device coordinates), in the order they were kept; they count as used by this frame. payload (if not
  // null) gets their payloads in the same order. Records marked as moved (mark_moved) that the view may see are not
  // among them: they go to `moved` (if not null) to be computed again, and are dropped here (stats().moved).
  std::vector<CacheRecord> for_view(const CameraParams& camera, const CacheSettings& cache,
                                    std::vector<float>* payload = nullptr, std::vector<CacheRecord>* moved = nullptr);
  // Keeps the records this frame placed (device coordinates) with their payloads (`payload_per_record` floats each;
  // the same count every frame while the key stays), then evicts the least recently used past the capacity. The first
  // `in_place` of them are records a move marked, computed again where they stood (computed_in_place_this_frame).
  void add(const CacheRecord* records, size_t count, const float* payload = nullptr, size_t payload_per_record = 0,
           size_t in_place = 0);
  // Radiance records: the brightest stratum any kept record saw (the radiance splat's bound), raised by each frame.
  float largest_radiance() const { return largest_radiance_; }
  void raise_largest_radiance(float value) { largest_radiance_ = std::max(largest_radiance_, value); }

  // Drops every record (and the brightest stratum) but keeps the key, so the light kept with them stays: a cache
  // pre-pass's key frame starts from no records (sequence/cache_merge.h).
  void drop_records();
  // Parts moved (issue 62): adds each move's bound (moved_record_change) to each record's change since it was made,
  // and marks the records whose sum passes `tolerance` as moved. A moved record stays where it is until a view takes
  // it: for_view then hands it out to be computed again in place (and drops it here; the frame adds what it
  // computes). A record beside a moving part (record_beside_move) is marked to go instead: for_view drops it, and
  // placement puts records where the view needs them. Returns how many were marked.
  // `only` (if not null): the indices of the records the moves apply to, the others left as they are (records of
  // different times, each group brought to the present by its own moves: sequence/record_times.h).
  size_t mark_moved(const std::vector<SweptBox>& moves, double tolerance, const std::vector<size_t>* only = nullptr);
  // A light moved: every record's light may have changed.
  size_t mark_all_moved(const std::vector<size_t>* only = nullptr);
  // The records marked to be computed again are marked to go instead: where a cache holds records of many times (a
  // merged pre-pass), a record that no longer holds has a newer one beside it or placement puts one there, cheaper
  // than computing it again in place. Returns how many.
  size_t let_marked_go();
  // Before a cache file is written of a moving scene: every open window closed with the record's light at the time
  // now (set_time), and the records marked to be computed again or to go dropped, since a file keeps no marks.
  // Returns the records dropped.
  size_t settle_for_file();
  // Temporal windows (issue 62 item 3). The time (seconds on the animation) of the frame the next moves, views and
  // windows belong to: a record with a window [start, end] is handed out by for_view with its light interpolated to
  // this time, and moves up to its end do not count against it (its light at the end already holds them). Past its
  // end, the next move settles it: its light becomes the end's and moves count again.
  void set_time(double seconds) { time_ = seconds; }
  double time() const { return time_; }
  // The records this frame computed again in place (add's in_place), in the order they were computed.
  std::vector<size_t> computed_in_place_this_frame() const;
  // Gives record `index` a window from now to `end`: its light there is `ahead`.
  void set_window(size_t index, const RecordLightAhead& ahead, double end);
  uint64_t windows_open() const;  // records whose window has not ended
  bool has_window(size_t index) const { return window_end_[index] > window_start_[index] && window_covers_now(index); }
  const KeptRecordsStats& stats() const { return stats_; }
  size_t size() const { return records_.size(); }
  void set_capacity(size_t capacity) { capacity_ = capacity; }

  // For cache files (sequence/cache_file.h): what is kept, the frame that last used each record, the frames begun.
  const std::vector<CacheRecord>& records() const { return records_; }
  const std::vector<uint64_t>& last_used() const { return last_used_; }
  const std::vector<float>& payload() const { return payload_; }
  size_t payload_per_record() const { return payload_per_record_; }
  uint64_t frames_begun() const { return frame_; }
  // What a cache file holds of one kind of records.
  struct Contents {
    std::vector<CacheRecord> records;
    std::vector<uint64_t> last_used;
    std::vector<float> payload;
    size_t payload_per_record = 0;
    float largest_radiance = 0.0f;
  };
  // Replaces what is kept with a cache file's records, computed with these settings.
  void restore(const KeptRecordsKey& key, Contents contents, uint64_t frames_begun);

 private:
  size_t capacity_;
  bool has_key_ = false;
  KeptRecordsKey key_;
  uint64_t frame_ = 0;
  std::vector<CacheRecord> records_;
  std::vector<uint64_t> last_used_;  // the last frame whose view took each record
  // The bound on how much moves have changed each record's light (mark_moved); +infinity: marked to be computed
  // again, -infinity: marked to go.
  std::vector<float> moved_change_;
  std::vector<uint64_t> in_place_frame_;   // the frame that computed the record again in place (0: none)
  std::vector<double> window_end_;         // where it has a window: its end (seconds); -infinity: none
  std::vector<double> window_start_;
  std::vector<RecordLightAhead> ahead_;    // its light at window_end_
  double time_ = 0.0;
  std::vector<float> payload_;       // payload_per_record_ floats a record
  size_t payload_per_record_ = 0;
  float largest_radiance_ = 0.0f;
  KeptRecordsStats stats_;
  void keep_only(const std::vector<char>& drop);
  void clear_records();
  void settle_window(size_t i);  // a window that ended: its light becomes the end's
  // Appends `count` records' bookkeeping: not marked, no window, used by this frame.
  void add_bookkeeping(size_t count, size_t in_place);
  bool window_covers_now(size_t i) const { return window_end_[i] >= time_; }
  // Record i with its light at the time now: interpolated across its window where it has one (ends held past them).
  CacheRecord light_now(size_t i) const;
  // Calls mark(i) for every record, or for those listed in `only`.
  template <typename Mark>
  void for_each_record(const std::vector<size_t>* only, Mark mark) {
    if (!only) {
      for (size_t i = 0; i < records_.size(); ++i) mark(i);
    } else {
      for (const size_t i : *only) mark(i);
    }
  }
};

// The light records read that does not depend on the view, as photons and clusters: what the photon map, the caustic
// map and the light guide were made from (render/indirect.h ViewIndependentLight). Kept beside the records so that a
// cache file carries the light its records were computed with, and a process reading it builds the maps from these
// photons in place of shooting them (on another device its own estimates of the same photons).
struct KeptLight {
  bool has_photon_map = false;
  uint64_t photon_paths = 0;
  std::vector<PhotonHit> photons;  // the photon map's landings, each round's share of the power applied
  bool has_caustic_map = false;
  std::vector<PhotonHit> caustic_photons;
  bool has_guide = false;
  uint64_t guide_hits = 0;
  std::vector<GuideCluster> guide_clusters;
};

// The time a cache's records hold (issue 62 item 5): nothing for a scene that stands still (animation -1); for one
// that glTF animation `animation` moves, either one time for every record (`time`, seconds: the frame a walkthrough
// with records kept ended on) or, by_key_frame, each record its key frame's (its last_used frame / fps: a cache
// pre-pass's part, a merged file). A process that reads them brings each record from its time to its frame's
// (sequence/record_times.h).
struct RecordTimes {
  int animation = -1;
  bool by_key_frame = false;
  double fps = 0.0;
  double time = 0.0;
  bool moving() const { return animation >= 0; }
  double of(uint64_t last_used) const { return by_key_frame ? double(last_used) / fps : time; }
  bool operator==(const RecordTimes&) const = default;
};

// What a walkthrough keeps (Renderer::kept_records): the irradiance records of the splat and the radiance records of
// the LOBE_HSH pixels, each with its own cap, the light they were computed with, and the time they hold.
struct KeptCache {
  explicit KeptCache(size_t capacity) : irradiance(capacity), radiance(capacity) {}
  void set_capacity(size_t capacity) {
    irradiance.set_capacity(capacity);
    radiance.set_capacity(capacity);
  }
  KeptRecords irradiance, radiance;
  KeptLight light;
  RecordTimes times;
};

}  // namespace rcsplat
