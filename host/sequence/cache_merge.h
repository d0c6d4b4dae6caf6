// The cache pre-pass of a walkthrough split over tasks (`animate --cache-every K`, `animate --cache-merge`; docs/FARM.md):
// each task renders the key frames of its range, each from no records, and writes a part file whose every record is
// tagged with its key frame (the file's per-record frame number). The merge makes one cache from the parts that is the
// same records in the same order whatever the split: records in key-frame order, each key frame's records in the order
// its frame placed them, a record dropped where a record of an earlier key frame already reaches it (kernels/
// cache_math.h record_reaches at the record's own position and normal, with the settings' accuracy).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "render/kept_records.h"

namespace rcsplat {

struct CachePart {
  std::string path;  // for messages
  const KeptCache* cache = nullptr;
};

struct CacheMergeStats {
  size_t key_frames = 0;
  size_t irradiance_in = 0, irradiance_kept = 0, radiance_in = 0, radiance_kept = 0;
};

// Whether a record of key frame `from` still holds at key frame `to` (a moving scene: sequence/record_times.h); an
// empty function: always (a scene that stands still).
using HoldsAt = std::function<bool(const CacheRecord& record, uint64_t from, uint64_t to)>;

// The records of `records` (tagged by `tags`, in key-frame order, a key frame's records together) that no record of an
// earlier key frame reaches (and, where `holds` is given, still holds at their key frame): a mask, 1 where kept.
std::vector<char> records_not_reached_earlier(const std::vector<CacheRecord>& records, const std::vector<uint64_t>& tags,
                                              float accuracy, const HoldsAt& holds = {});

// Merges pre-pass parts computed with `key` into `into` (replaced). Throws rcsplat::Error naming the files: parts whose
// light or times differ (another seed, device, version, animation or frame rate), a key frame in two parts, more
// records than `capacity`. A moving scene's parts (their times by key frame) need `holds`: an earlier key frame's
// record takes a later one's place only where it still holds there.
CacheMergeStats merge_cache_parts(const std::vector<CachePart>& parts, const KeptRecordsKey& key, size_t capacity,
                                  KeptCache& into, const HoldsAt& holds = {});

// What a pre-pass task writes: each key frame's records, in the order its frame placed them, tagged with the frame.
class PrePassPart {
 public:
  // A moving scene's part: each record holds its key frame's time, and the part keeps no light (each key frame
  // shot its own, where the scene stood at that frame).
  explicit PrePassPart(RecordTimes times = {}) : times_(times) {}
  // The records a key frame's renderer kept (it started from none). Throws rcsplat::Error when it evicted some.
  void add_key_frame(long long frame, const KeptCache& kept);
  // The part as a cache file holds it, with the light the key frames read. Throws rcsplat::Error past capacity.
  KeptCache cache(const KeptCache& kept, const KeptRecordsKey& key, size_t capacity) const;
  size_t irradiance_records() const { return irradiance_.records.size(); }
  size_t radiance_records() const { return radiance_.records.size(); }

 private:
  RecordTimes times_;
  KeptRecords::Contents irradiance_, radiance_;
  uint64_t frames_ = 0;
};

}  // namespace rcsplat
