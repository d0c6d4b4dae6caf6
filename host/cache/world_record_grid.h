// The splat's records by position in the world (kernels/world_records.h): a hashed grid over their reach spheres, for
// the glossy pass's reflections to read. Frames build it on the device (passes/world_record_grid_pass.h); this host
// build is the reference the device's must equal bit for bit (tests/world_records_test.cpp).
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
