#include "sequence/cache_merge.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "cache/octree_lookup.h"
#include "util/error.h"

namespace rcsplat {
namespace {

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_light(const KeptLight& a, const KeptLight& b) {
  return a.has_photon_map == b.has_photon_map && a.photon_paths == b.photon_paths && same_bytes(a.photons, b.photons) &&
         a.has_caustic_map == b.has_caustic_map && same_bytes(a.caustic_photons, b.caustic_photons) &&
         a.has_guide == b.has_guide && a.guide_hits == b.guide_hits && same_bytes(a.guide_clusters, b.guide_clusters);
}

// Cells of a uniform grid over the records' reach spheres: a record is listed in every cell its sphere overlaps, or,
// where that is more than kMostCells cells, in a list every query reads.
class ReachGrid {
 public:
  explicit ReachGrid(double cell) : cell_(cell) {}

  void insert(uint32_t record, const glm::vec3& centre, double reach) {
    int64_t lo[3], hi[3];
    uint64_t cells = 1;
    for (int a = 0; a < 3; ++a) {
      lo[a] = index(double(centre[a]) - reach);
      hi[a] = index(double(centre[a]) + reach);
      cells *= uint64_t(hi[a] - lo[a] + 1);
    }
    if (cells > kMostCells) {
      wide_.push_back(record);
      return;
    }
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) cells_[key(x, y, z)].push_back(record);
  }

  // Calls visit(record) for every record whose sphere may hold p, until it returns true; whether one did.
  template <typename Visit>
  bool any(const glm::vec3& p, Visit visit) const {
    for (uint32_t k : wide_)
      if (visit(k)) return true;
    const auto found = cells_.find(key(index(p.x), index(p.y), index(p.z)));
    if (found == cells_.end()) return false;
    for (uint32_t k : found->second)
      if (visit(k)) return true;
    return false;
  }

 private:
  static constexpr uint64_t kMostCells = 64;
  static constexpr int64_t kHalfRange = int64_t(1) << 20;  // 21 bits an axis; beyond, cells merge (more candidates)
  int64_t index(double v) const {
    const double i = std::floor(v / cell_);
    return int64_t(std::clamp(i, double(-kHalfRange), double(kHalfRange - 1)));
  }
  static uint64_t key(int64_t x, int64_t y, int64_t z) {
    return (uint64_t(x + kHalfRange) << 42) | (uint64_t(y + kHalfRange) << 21) | uint64_t(z + kHalfRange);
  }
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
  std::vector<uint32_t> wide_;
};

// One kind of records of every part, in key-frame order, thinned.
KeptRecords::Contents merge_kind(const std::vector<CachePart>& parts, KeptRecords KeptCache::*kind, float accuracy,
                                 const HoldsAt& holds, size_t& records_in) {
  struct Entry {
    uint64_t tag;
    size_t part, index;
  };
  std::vector<Entry> entries;
  for (size_t p = 0; p < parts.size(); ++p) {
    const std::vector<uint64_t>& tags = (parts[p].cache->*kind).last_used();
    for (size_t i = 0; i < tags.size(); ++i) entries.push_back({tags[i], p, i});
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
  records_in = entries.size();
  std::vector<CacheRecord> records(entries.size());
  std::vector<uint64_t> tags(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) {
    records[e] = (parts[entries[e].part].cache->*kind).records()[entries[e].index];
    tags[e] = entries[e].tag;
  }
  const std::vector<char> keep = records_not_reached_earlier(records, tags, accuracy, holds);
  KeptRecords::Contents out;
  for (const CachePart& part : parts)
    if (!(part.cache->*kind).records().empty()) out.payload_per_record = (part.cache->*kind).payload_per_record();
  for (const CachePart& part : parts) {
    const KeptRecords& r = part.cache->*kind;
    if (!r.records().empty() && r.payload_per_record() != out.payload_per_record)
      throw Error(part.path + ": its radiance records carry another number of coefficients than the other parts'");
    out.largest_radiance = std::max(out.largest_radiance, r.largest_radiance());
  }
  for (size_t e = 0; e < entries.size(); ++e) {
    if (!keep[e]) continue;
    out.records.push_back(records[e]);
    out.last_used.push_back(tags[e]);
    const KeptRecords& from = parts[entries[e].part].cache->*kind;
    const float* payload = from.payload().data() + entries[e].index * out.payload_per_record;
    out.payload.insert(out.payload.end(), payload, payload + out.payload_per_record);
  }
  return out;
}

}  // namespace

std::vector<char> records_not_reached_earlier(const std::vector<CacheRecord>& records, const std::vector<uint64_t>& tags,
                                              float accuracy, const HoldsAt& holds) {
  const size_t n = records.size();
  std::vector<char> keep(n, 1);
  if (n == 0) return keep;
  if (!std::is_sorted(tags.begin(), tags.end())) throw std::logic_error("records_not_reached_earlier: unsorted tags");
  // Ward's weight exceeds 1/a only within a radii of the record: a record's reach sphere.
  std::vector<double> reach(n);
  for (size_t i = 0; i < n; ++i) reach[i] = double(accuracy) * double(records[i].radius);
  std::vector<double> sorted = reach;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  ReachGrid grid(std::max(sorted[n / 2], 1e-6));
  for (size_t begin = 0; begin < n;) {
    size_t end = begin;
    while (end < n && tags[end] == tags[begin]) ++end;
    for (size_t i = begin; i < end; ++i) {
      const PixelGeometry at{record_position(records[i]), record_normal(records[i]), true};
      keep[i] = !grid.any(at.p, [&](uint32_t k) {
        const CacheRecord& r = records[k];
        const glm::vec3 pk = record_position(r), nk = record_normal(r);
        return record_reaches_pixel(r, ward_weight(at.p, at.n, pk, nk, r.radius), accuracy, at, pk, nk) &&
               (!holds || holds(r, tags[k], tags[i]));
      });
    }
    for (size_t i = begin; i < end; ++i)
      if (keep[i]) grid.insert(uint32_t(i), record_position(records[i]), reach[i]);
    begin = end;
  }
  return keep;
}

CacheMergeStats merge_cache_parts(const std::vector<CachePart>& parts, const KeptRecordsKey& key, size_t capacity,
                                  KeptCache& into, const HoldsAt& holds) {
  if (parts.empty()) throw Error("--cache-merge: no part files to merge");
  for (size_t p = 1; p < parts.size(); ++p) {
    if (!same_light(parts[0].cache->light, parts[p].cache->light))
      throw Error(parts[p].path + ": its photons and light guide differ from " + parts[0].path +
                  "'s: every part of a pre-pass must come from the same settings, rcsplat and kind of device");
    if (!(parts[0].cache->times == parts[p].cache->times))
      throw Error(parts[p].path + ": its records' times differ from " + parts[0].path +
                  "'s (another animation or frame rate): every part of a pre-pass must come from the same walkthrough");
  }
  const RecordTimes& times = parts[0].cache->times;
  if (times.moving() && (!times.by_key_frame || !holds))
    throw Error(parts[0].path + ": not a pre-pass part of a moving scene (its records hold one time, not their key "
                "frames')");
  // A key frame in two parts would be kept twice (overlapping frame ranges).
  std::map<uint64_t, size_t> owner;
  for (size_t p = 0; p < parts.size(); ++p)
    for (const KeptRecords* kind : {&parts[p].cache->irradiance, &parts[p].cache->radiance})
      for (uint64_t tag : kind->last_used()) {
        const auto [it, added] = owner.emplace(tag, p);
        if (!added && it->second != p)
          throw Error(parts[p].path + " and " + parts[it->second].path + ": both hold key frame " +
                      std::to_string(tag) + "; the parts' frame ranges must not overlap");
      }
  CacheMergeStats stats;
  stats.key_frames = owner.size();
  const HoldsAt& still_holds = times.moving() ? holds : HoldsAt{};
  KeptRecords::Contents irradiance =
      merge_kind(parts, &KeptCache::irradiance, key.cache.accuracy, still_holds, stats.irradiance_in);
  KeptRecords::Contents radiance = merge_kind(parts, &KeptCache::radiance, key.cache.accuracy, still_holds, stats.radiance_in);
  stats.irradiance_kept = irradiance.records.size();
  stats.radiance_kept = radiance.records.size();
  if (stats.irradiance_kept > capacity || stats.radiance_kept > capacity)
    throw Error("--cache-merge: " + std::to_string(std::max(stats.irradiance_kept, stats.radiance_kept)) +
                " records after thinning, more than --kept-records " + std::to_string(capacity) +
                " (give a larger --kept-records here and to every animate that reads the file)");
  const uint64_t frames = owner.empty() ? 0 : owner.rbegin()->first + 1;
  into = KeptCache(capacity);
  into.irradiance.restore(key, std::move(irradiance), frames);
  into.radiance.restore(key, std::move(radiance), frames);
  into.light = parts[0].cache->light;
  into.times = times;
  return stats;
}

void PrePassPart::add_key_frame(long long frame, const KeptCache& kept) {
  for (auto [from, to] : {std::pair{&kept.irradiance, &irradiance_}, std::pair{&kept.radiance, &radiance_}}) {
    if (from->stats().evicted)
      throw Error("--cache-every: key frame " + std::to_string(frame) + " placed more records than --kept-records " +
                  "keeps; give a larger --kept-records here, to the merge and to every animate that reads the file");
    to->records.insert(to->records.end(), from->records().begin(), from->records().end());
    to->last_used.insert(to->last_used.end(), from->records().size(), uint64_t(frame));
    to->payload.insert(to->payload.end(), from->payload().begin(), from->payload().end());
    if (!from->records().empty()) to->payload_per_record = from->payload_per_record();
    to->largest_radiance = std::max(to->largest_radiance, from->largest_radiance());
  }
  frames_ = uint64_t(frame) + 1;
}

KeptCache PrePassPart::cache(const KeptCache& kept, const KeptRecordsKey& key, size_t capacity) const {
  if (irradiance_.records.size() > capacity || radiance_.records.size() > capacity)
    throw Error("--cache-every: the key frames placed " +
                std::to_string(std::max(irradiance_.records.size(), radiance_.records.size())) +
                " records, more than --kept-records " + std::to_string(capacity) +
                "; give a larger --kept-records here, to the merge and to every animate that reads the file");
  KeptCache out(capacity);
  out.irradiance.restore(key, irradiance_, frames_);
  out.radiance.restore(key, radiance_, frames_);
  out.light = times_.moving() ? KeptLight{} : kept.light;
  out.times = times_;
  return out;
}

}  // namespace rcsplat
