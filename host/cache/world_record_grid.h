// The splat's records by position in the world (kernels/world_records.h): a hashed grid over their reach spheres,
// built on the host each frame from the records the splat used, for the glossy pass's reflections to read.
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/shared_types.h"

namespace rcsplat {

struct WorldRecordGrid {
  WorldRecordParams params{};
  std::vector<uint32_t> bucket_starts;  // params.bucket_count + 1
  std::vector<uint32_t> record_lists;   // record indices, each once per bucket, ascending within it
};

// The grid of these records at the splat's accuracy, with the splat's bound on extrapolated irradiance derived from
// them as the splat derives it (fixed_point_irradiance_scale of the largest component). Its cell is as wide as the median reach
// sphere (so that most spheres meet at most 8 cells), and at least an eighth of the widest (so that none meets more
// than 10^3). Records with a non-finite or non-positive radius are left out. Deterministic: the same records give the
// same grid.
WorldRecordGrid build_world_record_grid(const std::vector<CacheRecord>& records, float accuracy);

}  // namespace rcsplat
