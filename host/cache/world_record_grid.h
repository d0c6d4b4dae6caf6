// The splat's records by position in the world (kernels/world_records.h): a hashed grid over their reach spheres, for
// the glossy pass's reflections to read, as the host holds it. Frames build it on the device
// (passes/world_record_grid_pass.h); the tests' double-checked host build (tests/reference/world_record_grid.h) is the
// reference the device's must equal bit for bit (tests/world_records_test.cpp).
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

}  // namespace rcsplat
