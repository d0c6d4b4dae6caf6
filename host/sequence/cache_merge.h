// The cache pre-pass of a walkthrough split over tasks (`animate --cache-every K`, `animate --cache-merge`; docs/FARM.md):
// each task renders the key frames of its range, each from no records, and writes a part file whose every record is
// tagged with its key frame (the file's per-record frame number). The merge makes one cache from the parts that is the
// same records in the same order whatever the split: records in key-frame order, each key frame's records in the order
// its frame placed them, a record dropped where a record of an earlier key frame already reaches it (kernels/
// cache_math.h record_reaches at the record's own position and normal, with the settings' accuracy).
#pragma once
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

// The records of `records` (tagged by `tags`, in key-frame order, a key frame's records together) that no record of an
// earlier key frame reaches: a mask, 1 where kept.
std::vector<char> records_not_reached_earlier(const std::vector<CacheRecord>& records, const std::vector<uint64_t>& tags,
                                              float accuracy);

// Merges pre-pass parts computed with `key` into `into` (replaced). Throws rcsplat::Error naming the files: parts whose
// light differs (another seed, device or version), a key frame in two parts, more records than `capacity`.
CacheMergeStats merge_cache_parts(const std::vector<CachePart>& parts, const KeptRecordsKey& key, size_t capacity,
                                  KeptCache& into);

// What a pre-pass task writes: each key frame's records, in the order its frame placed them, tagged with the frame.
class PrePassPart {
 public:
  // The records a key frame's renderer kept (it started from none). Throws rcsplat::Error when it evicted some.
  void add_key_frame(long long frame, const KeptCache& kept);
  // The part as a cache file holds it, with the light the key frames read. Throws rcsplat::Error past capacity.
  KeptCache cache(const KeptCache& kept, const KeptRecordsKey& key, size_t capacity) const;
  size_t irradiance_records() const { return irradiance_.records.size(); }
  size_t radiance_records() const { return radiance_.records.size(); }

 private:
  KeptRecords::Contents irradiance_, radiance_;
  uint64_t frames_ = 0;
};

}  // namespace rcsplat
