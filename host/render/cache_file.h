// Cache files (`--cache-out FILE`, `--cache-in FILE` for `render` and `animate`): the irradiance records a Renderer
// keeps across frames (render/kept_records.h), so that another process goes on from them. A frame rendered from a
// loaded cache is the same bits as the same frame rendered by the process that wrote it, on the same kind of device:
// the photon map, caustic map and light guide the records were computed with are not stored but made again from the
// same seed, which gives the same bits on the same device and the same light within its noise on another.
//
// Format (little-endian; docs/USAGE.md "Cache files"):
//   16 bytes  "rcsplat cache\0\0\0"
//   u32       format version (1), u32 bytes a record (160)
//   32 bytes  the rcsplat version that wrote it, zero-padded: records change with the code that computes them
//   u64       the scene's fingerprint (scene_fingerprint), u64 the settings' (settings_fingerprint)
//   u64       frames begun, u64 record count N
//   64 bytes  the device that computed them, zero-padded (for messages)
//   N records (CacheRecord, device coordinates), N u64 (the frame that last used each)
//   u64       FNV-1a of every byte before it
// Every file is read as a stranger's: its size is checked against N before anything is allocated, N against the
// cap, the checksum before anything else is believed, and every record's numbers before it is kept.
#pragma once
#include <cstdint>
#include <string>

#include "render/kept_records.h"
#include "scene/scene.h"

namespace rcsplat {

// Every number of the scene that records depend on: geometry, materials, textures, lights, the environment.
uint64_t scene_fingerprint(const Scene& scene);
// The settings records are computed with (kept_records_key of a frame's settings).
uint64_t settings_fingerprint(const KeptRecordsKey& key);

struct CacheFileIdentity {
  uint64_t scene = 0, settings = 0;
  std::string device;
};

// Writes the kept records (atomically: util/atomic_file.h). Throws rcsplat::Error naming the file.
void write_cache_file(const std::string& path, const KeptRecords& kept, const CacheFileIdentity& identity);
// Reads a cache file into `into` (its records replace what it holds) for these settings. Throws rcsplat::Error naming
// the file and the problem: not a cache file, another format or rcsplat version, another scene, other settings, more
// records than `capacity`, truncated, damaged (its checksum), or a record whose numbers are out of range.
void read_cache_file(const std::string& path, const CacheFileIdentity& expected, const KeptRecordsKey& key,
                     size_t capacity, KeptRecords& into);

}  // namespace rcsplat
