// Cache files (`--cache-out FILE`, `--cache-in FILE` for `render` and `animate`): what a Renderer keeps across frames
// (render/kept_records.h: irradiance records, radiance records with their HSH coefficients, and the photons and
// clusters the photon map, caustic map and light guide were made from), so that another process goes on from them. A
// frame rendered from a loaded cache is the same bits as the same frame rendered by the process that wrote it, on the
// same kind of device. On another device the records and photons are the writer's; the reader's device computes the
// maps' estimates from those photons, the new records and the pixels, so its frames differ from the writer's by its
// own float rounding (scene, settings and rcsplat version must match; the device need not).
//
// Format 3 (little-endian; docs/USAGE.md "Cache files"):
//   16 bytes  "rcsplat cache\0\0\0"
//   u32       format version (3), u32 bytes a record (160)
//   32 bytes  the rcsplat version that wrote it, zero-padded: records change with the code that computes them
//   u64       the scene's fingerprint (scene_fingerprint), u64 the settings' (settings_fingerprint)
//   u64       frames begun
//   64 bytes  the device that computed them, zero-padded (for messages)
//   i32       the glTF animation that moves the scene (-1: it stands still), u32 1 where each record holds its key
//             frame's time (its u64 below / fps), f64 frames a second, f64 the time every record holds otherwise
//             (render/kept_records.h RecordTimes; all zero for a scene that stands still)
//   irradiance records: u64 N, N records (CacheRecord, device coordinates), N u64 (the frame that last used each)
//   radiance records:   u64 N, u32 F floats a record, f32 the brightest stratum any of them saw, N records, N u64,
//                       N x F floats (HSH coefficients, kernels/hsh_records.cl's layout)
//   photon map:         u32 present, u64 paths shot, u64 M, M photons (PhotonHit)
//   caustic map:        u32 present, u64 M, M photons
//   light guide:        u32 present, u64 photons that hit, u64 K, K clusters (GuideCluster)
//   u64       FNV-1a of every byte before it
// Every file is read as a stranger's: every count is checked against the file's size before anything is allocated,
// the checksum before anything else is believed, then the counts against what these settings can make, and every
// record's, photon's and cluster's numbers before it is kept.
#pragma once
#include <cstdint>
#include <string>

#include "render/kept_records.h"
#include "render/settings.h"
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

// The most a cache file may hold for a frame's settings: records of each kind (--kept-records), a radiance record's
// floats (its HSH order), and the photons the settings shoot at most.
struct CacheFileLimits {
  size_t records = 0, radiance_floats = 0, photons = 0, caustic_photons = 0;
};
CacheFileLimits cache_file_limits(const RenderSettings& frame_settings);

// Writes what is kept (atomically: util/atomic_file.h). Throws rcsplat::Error naming the file.
void write_cache_file(const std::string& path, const KeptCache& kept, const CacheFileIdentity& identity);
// Reads a cache file into `into` (what it holds is replaced) for these settings. Throws rcsplat::Error naming the file
// and the problem: not a cache file, another format or rcsplat version, another scene, other settings, more records or
// photons than these settings keep, truncated or padded, damaged (its checksum), or numbers out of range.
void read_cache_file(const std::string& path, const CacheFileIdentity& expected, const KeptRecordsKey& key,
                     const CacheFileLimits& limits, KeptCache& into);

}  // namespace rcsplat
