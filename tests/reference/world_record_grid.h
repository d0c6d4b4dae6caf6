// The tests' reference build of the records' world grid (cache/world_record_grid.h): the host's own, written apart
// from the device's kernels (kernels/world_record_grid.cl), which must equal it bit for bit
// (tests/world_records_test.cpp).
#pragma once
#include <vector>

#include "cache/world_record_grid.h"

namespace rcsplat {

// The grid of these records at the splat's accuracy, with the splat's bound on extrapolated irradiance derived from
// them as the splat derives it (fixed_point_irradiance_scale of the largest component). Its cell is as wide as the median reach
// sphere (so that most spheres meet at most 8 cells), and at least an eighth of the widest (so that none meets more
// than 10^3). Records with a non-finite or non-positive radius are left out. Deterministic: the same records give the
// same grid.
WorldRecordGrid build_world_record_grid(const std::vector<CacheRecord>& records, float accuracy);

}  // namespace rcsplat
