#include "render/kept_records.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <numeric>
#include <stdexcept>

#include "kernels/cache_math.h"

namespace rcsplat {
namespace {

glm::dvec3 load(const float* v) { return {v[0], v[1], v[2]}; }

// Whether a sphere may show in the view: within `reach` of each side of its frustum (the near side at the eye).
bool sphere_meets_view(const CameraParams& c, const glm::dvec3& centre, double reach) {
  const glm::dvec3 d = centre - load(c.eye);
  const double x = glm::dot(d, load(c.right)), y = glm::dot(d, load(c.up)), z = glm::dot(d, load(c.forward));
  const double aspect = double(c.aspect);
  if (c.orthographic) {
    const double h = double(c.half_height);
    return z > -reach && std::fabs(x) <= h * aspect + reach && std::fabs(y) <= h + reach;
  }
  if (z < -reach) return false;
  // A side plane through the eye, |x| = z t: the signed distance of the centre beyond it is (|x| - z t) / sqrt(1 +
  // t^2).
  const double ty = double(c.tan_half_fov_y), tx = ty * aspect;
  return (std::fabs(x) - z * tx) <= reach * std::sqrt(1.0 + tx * tx) &&
         (std::fabs(y) - z * ty) <= reach * std::sqrt(1.0 + ty * ty);
}

}  // namespace

KeptRecordsKey kept_records_key(const RenderSettings& s) {
  KeptRecordsKey k;
  k.cache = s.cache;
  k.seed = s.seed;
  k.bounces = s.bounces;
  k.photon_paths = s.photon_paths;
  k.photon_neighbours = s.photon_neighbours;
  k.caustic_photons = s.caustic_photons;
  k.sub_pixel_side = s.sub_pixel_side;
  k.bounce_method = s.bounce_method;
  k.short_ray_paths = s.short_ray_paths;
  k.photon_min_support = s.photon_min_support;
  k.hsh_order = s.hsh_order;
  return k;
}

bool KeptRecords::begin_frame(const KeptRecordsKey& key) {
  const bool dropped = !has_key_ || !(key == key_);
  if (dropped) {
    clear_records();
    payload_per_record_ = 0;
    largest_radiance_ = 0.0f;
    key_ = key;
    has_key_ = true;
  }
  ++frame_;
  stats_ = KeptRecordsStats{};
  stats_.capacity = capacity_;
  return dropped;
}

std::vector<CacheRecord> KeptRecords::for_view(const CameraParams& camera, const CacheSettings& cache,
                                               std::vector<float>* payload, std::vector<CacheRecord>* moved) {
  std::vector<CacheRecord> taken;
  if (payload) payload->clear();
  if (moved) moved->clear();
  std::vector<char> drop(records_.size(), 0);
  size_t dropped = 0;
  const double accuracy = double(cache.accuracy), smallest = double(cache.min_reach_pixels);
  for (size_t i = 0; i < records_.size(); ++i) {
    const CacheRecord& r = records_[i];
    const glm::dvec3 p = load(r.position);
    const double footprint = pixel_world_size(&camera, glm::vec3(p));  // as the kernel's fit takes it
    // Fitting (kernels/placement.cl) never takes a reach below the view's minimum nor above the kept one.
    const double reach = std::max(accuracy * double(r.radius), 1.01 * smallest * footprint);
    if (!sphere_meets_view(camera, p, reach)) continue;
    if (std::isinf(moved_change_[i])) {
      if (moved && moved_change_[i] > 0.0f) moved->push_back(r);
      drop[i] = 1;
      ++dropped;
      continue;
    }
    taken.push_back(light_now(i));
    if (payload)
      payload->insert(payload->end(), payload_.begin() + std::ptrdiff_t(i * payload_per_record_),
                      payload_.begin() + std::ptrdiff_t((i + 1) * payload_per_record_));
    last_used_[i] = frame_;
  }
  if (dropped) keep_only(drop);
  stats_.reused = taken.size();
  stats_.moved = dropped;
  return taken;
}

void KeptRecords::clear_records() {
  records_.clear();
  last_used_.clear();
  moved_change_.clear();
  in_place_frame_.clear();
  window_end_.clear();
  window_start_.clear();
  ahead_.clear();
  payload_.clear();
}

void KeptRecords::add_bookkeeping(size_t count, size_t in_place) {
  moved_change_.insert(moved_change_.end(), count, 0.0f);
  in_place_frame_.insert(in_place_frame_.end(), count, 0);
  std::fill(in_place_frame_.end() - std::ptrdiff_t(count), in_place_frame_.end() - std::ptrdiff_t(count - in_place),
            frame_);
  window_end_.insert(window_end_.end(), count, -INFINITY);
  window_start_.insert(window_start_.end(), count, -INFINITY);
  ahead_.insert(ahead_.end(), count, RecordLightAhead{});
}

void KeptRecords::drop_records() {
  clear_records();
  largest_radiance_ = 0.0f;
}

void KeptRecords::restore(const KeptRecordsKey& key, Contents contents, uint64_t frames_begun) {
  key_ = key;
  has_key_ = true;
  records_ = std::move(contents.records);
  last_used_ = std::move(contents.last_used);
  moved_change_.clear();
  in_place_frame_.clear();
  window_end_.clear();
  window_start_.clear();
  ahead_.clear();
  add_bookkeeping(records_.size(), 0);
  payload_ = std::move(contents.payload);
  payload_per_record_ = contents.payload_per_record;
  largest_radiance_ = contents.largest_radiance;
  frame_ = frames_begun;
}

void KeptRecords::add(const CacheRecord* records, size_t count, const float* payload, size_t payload_per_record,
                      size_t in_place) {
  if (!records_.empty() && payload_per_record != payload_per_record_)
    throw std::logic_error("kept records: a payload of another size under the same key");
  payload_per_record_ = payload_per_record;
  if (count) records_.insert(records_.end(), records, records + count);
  last_used_.insert(last_used_.end(), count, frame_);
  add_bookkeeping(count, std::min(in_place, count));
  if (payload_per_record && count) payload_.insert(payload_.end(), payload, payload + count * payload_per_record);
  stats_.added = count;
  stats_.in_place = in_place;
  if (records_.size() > capacity_) {
    // The least recently used go first; among records last used by the same frame, the earliest kept.
    std::vector<size_t> order(records_.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return last_used_[a] < last_used_[b]; });
    std::vector<char> drop(records_.size(), 0);
    const size_t excess = records_.size() - capacity_;
    for (size_t k = 0; k < excess; ++k) drop[order[k]] = 1;
    keep_only(drop);
    stats_.evicted = excess;
  }
  stats_.kept = records_.size();
}

void KeptRecords::keep_only(const std::vector<char>& drop) {
  size_t kept = 0;
  for (size_t i = 0; i < records_.size(); ++i)
    if (!drop[i]) {
      records_[kept] = records_[i];
      last_used_[kept] = last_used_[i];
      moved_change_[kept] = moved_change_[i];
      in_place_frame_[kept] = in_place_frame_[i];
      window_end_[kept] = window_end_[i];
      window_start_[kept] = window_start_[i];
      ahead_[kept] = ahead_[i];
      std::copy_n(payload_.begin() + std::ptrdiff_t(i * payload_per_record_), payload_per_record_,
                  payload_.begin() + std::ptrdiff_t(kept * payload_per_record_));
      ++kept;
    }
  records_.resize(kept);
  last_used_.resize(kept);
  moved_change_.resize(kept);
  in_place_frame_.resize(kept);
  window_end_.resize(kept);
  window_start_.resize(kept);
  ahead_.resize(kept);
  payload_.resize(kept * payload_per_record_);
}

CacheRecord KeptRecords::light_now(size_t i) const {
  if (window_end_[i] <= window_start_[i]) return records_[i];
  return interpolated(records_[i], ahead_[i], (time_ - window_start_[i]) / (window_end_[i] - window_start_[i]));
}

void KeptRecords::settle_window(size_t i) {
  if (window_end_[i] <= window_start_[i]) return;
  records_[i] = interpolated(records_[i], ahead_[i], 1.0);
  window_end_[i] = window_start_[i] = -INFINITY;
}

size_t KeptRecords::mark_moved(const std::vector<SweptBox>& moves, double tolerance, const std::vector<size_t>* only) {
  size_t count = 0;
  for_each_record(only, [&](size_t i) {
    if (std::isinf(moved_change_[i])) return;
    // Beside a moving part, what the record stands on and what hides it changed: it goes, and placement puts records
    // where the view now needs them, window or not (an interpolation would miss the contact).
    if (record_beside_any(records_[i], moves)) {
      moved_change_[i] = -INFINITY;
      ++count;
      return;
    }
    if (window_covers_now(i)) return;  // its light at the window's end holds this move
    settle_window(i);
    const double change = moved_record_change(records_[i], moves, double(moved_change_[i]));
    // Farther off only its light changed: it is computed again where it stands.
    moved_change_[i] = change > tolerance ? INFINITY : float(change);
    count += change > tolerance;
  });
  return count;
}

size_t KeptRecords::mark_all_moved(const std::vector<size_t>* only) {
  size_t count = 0;
  for_each_record(only, [&](size_t i) {
    if (std::isinf(moved_change_[i]) || window_covers_now(i)) return;
    settle_window(i);
    moved_change_[i] = INFINITY;
    ++count;
  });
  return count;
}

size_t KeptRecords::let_marked_go() {
  size_t count = 0;
  for (float& change : moved_change_)
    if (change == INFINITY) change = -INFINITY, ++count;
  return count;
}

size_t KeptRecords::settle_for_file() {
  std::vector<char> drop(records_.size(), 0);
  size_t dropped = 0;
  for (size_t i = 0; i < records_.size(); ++i) {
    records_[i] = light_now(i);
    window_end_[i] = window_start_[i] = -INFINITY;
    drop[i] = std::isinf(moved_change_[i]);
    dropped += drop[i];
  }
  if (dropped) keep_only(drop);
  return dropped;
}

std::vector<size_t> KeptRecords::computed_in_place_this_frame() const {
  std::vector<size_t> indices;
  for (size_t i = 0; i < records_.size(); ++i)
    if (in_place_frame_[i] == frame_ && frame_ > 0) indices.push_back(i);
  return indices;
}

void KeptRecords::set_window(size_t index, const RecordLightAhead& ahead, double end) {
  ahead_[index] = ahead;
  window_start_[index] = time_;
  window_end_[index] = end;
  moved_change_[index] = 0.0f;
}

uint64_t KeptRecords::windows_open() const {
  uint64_t open = 0;
  for (size_t i = 0; i < records_.size(); ++i) open += window_end_[i] > window_start_[i] && window_covers_now(i);
  return open;
}

RecordLightAhead light_of(const CacheRecord& record) {
  RecordLightAhead light;
  std::copy_n(record.irradiance, 3, light.irradiance);
  std::copy_n(record.grad_translation, 9, light.grad_translation);
  std::copy_n(record.grad_rotation, 9, light.grad_rotation);
  return light;
}

CacheRecord interpolated(const CacheRecord& record, const RecordLightAhead& ahead, double s) {
  const float t = float(std::clamp(s, 0.0, 1.0));
  CacheRecord r = record;
  auto lerp = [t](float* to, const float* from, int n) {
    for (int k = 0; k < n; ++k) to[k] = (1.0f - t) * to[k] + t * from[k];  // the ends exactly at t = 0 and 1
  };
  lerp(r.irradiance, ahead.irradiance, 3);
  lerp(r.grad_translation, ahead.grad_translation, 9);
  lerp(r.grad_rotation, ahead.grad_rotation, 9);
  return r;
}

double distance_to_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  // The closest point by the region of the triangle's plane p projects into: a corner, an edge, or the inside.
  const glm::dvec3 ab = b - a, ac = c - a;
  const double d1 = glm::dot(ab, p - a), d2 = glm::dot(ac, p - a);
  const double d3 = glm::dot(ab, p - b), d4 = glm::dot(ac, p - b);
  const double d5 = glm::dot(ab, p - c), d6 = glm::dot(ac, p - c);
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  glm::dvec3 closest;
  if (d1 <= 0.0 && d2 <= 0.0) {
    closest = a;
  } else if (d3 >= 0.0 && d4 <= d3) {
    closest = b;
  } else if (d6 >= 0.0 && d5 <= d6) {
    closest = c;
  } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    closest = a + ab * (d1 / (d1 - d3));
  } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    closest = a + ac * (d2 / (d2 - d6));
  } else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    closest = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  } else {
    const double sum = va + vb + vc;
    closest = a + ab * (vb / sum) + ac * (vc / sum);
  }
  const double d = glm::length(p - closest);
  if (std::isfinite(d)) return d;
  // A degenerate triangle (a divide by zero above): its corners and edges' ends bound it well enough.
  return std::min({glm::length(p - a), glm::length(p - b), glm::length(p - c)});
}

bool record_beside_move(const CacheRecord& record, const SweptBox& swept) {
  // The distance from the record to the box the part filled before and after the move: the box, not the sphere
  // around it, so that a thin part (a door) leaves the records across the room to be computed in place.
  const glm::dvec3 p = load(record.position);
  const glm::dvec3 outside = glm::max(glm::max(glm::dvec3(swept.lo) - p, p - glm::dvec3(swept.hi)), glm::dvec3(0.0));
  if (!(glm::length(outside) <= double(record.radius))) return false;
  if (swept.triangles.empty() || !std::isfinite(swept.displacement)) return true;
  const double reach = double(record.radius) + double(swept.displacement);
  for (size_t t = 0; t + 2 < swept.triangles.size(); t += 3)
    if (distance_to_triangle(p, glm::dvec3(swept.triangles[t]), glm::dvec3(swept.triangles[t + 1]),
                             glm::dvec3(swept.triangles[t + 2])) <= reach)
      return true;
  return false;
}

bool record_beside_any(const CacheRecord& record, const std::vector<SweptBox>& moves) {
  for (const SweptBox& move : moves)
    if (record_beside_move(record, move)) return true;
  return false;
}

double moved_record_change(const CacheRecord& record, const std::vector<SweptBox>& moves, double before) {
  double change = before;
  for (const SweptBox& move : moves) change += moved_record_change(record, move);
  return change;
}

double moved_record_change(const CacheRecord& record, const SweptBox& swept) {
  if (record_beside_move(record, swept)) return 1.0;
  const glm::dvec3 lo(swept.lo), hi(swept.hi);
  const glm::dvec3 centre = 0.5 * (lo + hi), p = load(record.position), n = load(record.normal);
  const double radius = 0.5 * glm::length(hi - lo);
  const glm::dvec3 to = centre - p;
  const double d = glm::length(to);
  if (!(d > radius)) return 1.0;  // inside the sphere around the box: the part may fill any share of the hemisphere
  const double sin_a = radius / d, a = std::asin(sin_a);
  const double theta = std::acos(std::clamp(glm::dot(n, to) / (d * std::max(glm::length(n), 1e-30)), -1.0, 1.0));
  if (theta - a >= 0.5 * M_PI) return 0.0;  // wholly below the horizon
  // Two discs of angular radius a whose centres are delta / d apart differ by about 4 a (delta / d) of the sphere.
  const double band = 4.0 / M_PI * sin_a * double(swept.displacement) / d;  // infinite displacement: the whole sphere
  return std::min(sin_a * sin_a, band) * std::cos(std::max(theta - a, 0.0));
}

}  // namespace rcsplat
