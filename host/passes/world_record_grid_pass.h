// The glossy pass's grid of the splat's records by position (kernels/world_record_grid.cl), built on the device
// where the records are: the same grid as the tests' host build (tests/reference/world_record_grid.h build_world_record_grid), bit for
// bit, with 36 bytes read back (its parameters and the count of its entries, which size the buckets). Owns the grid's
// buffers and its scratch, kept for the next frame.
#pragma once
#include <cstdint>

#include "cache/world_record_grid.h"
#include "cl/gpu_context.h"
#include "passes/grid_sort_pass.h"
#include "passes/scan_pass.h"

namespace rcsplat {

// A grid on the device over records on the device (kernels/world_records.h WORLD_RECORD_ARGS). The buffers belong to
// whoever built it and hold until its next build.
struct DeviceWorldRecordGrid {
  WorldRecordParams params{};
  const cl::Buffer* records = nullptr;
  const cl::Buffer* bucket_starts = nullptr;  // params.bucket_count + 1
  const cl::Buffer* record_lists = nullptr;
};

class WorldRecordGridPass {
 public:
  explicit WorldRecordGridPass(GpuContext& gpu);
  // Starts building its programs (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // The grid of records 0 .. record_count - 1 of `records` at the splat's accuracy.
  DeviceWorldRecordGrid build(const cl::Buffer& records, uint32_t record_count, float accuracy);

 private:
  static constexpr const char* kProgram = "world_record_grid.cl";  // its kernels' file
  // `buffer` holding at least `count` uints (GpuContext::reserve).
  void reserve(cl::Buffer& buffer, size_t& capacity, size_t count);

  GpuContext& gpu_;
  GridSortPass sort_;
  ScanPass scan_;
  NamedKernel measure_, count_digits_, choose_digit_, lay_out_, count_cells_, write_cells_, mark_first_, write_lists_;
  cl::Buffer extent_, bins_, params_;
  // Per record: its cells, then where its entries start; per entry: its bucket and record, whether it is its record's
  // first in the bucket and where it goes in the lists; per bucket: entries' starts (the sort's), lists' counts.
  cl::Buffer cells_, cell_places_, entry_bucket_, entry_record_, first_, list_places_, entry_starts_, list_counts_;
  cl::Buffer bucket_starts_, record_lists_;
  size_t cells_capacity_ = 0, cell_places_capacity_ = 0, entry_bucket_capacity_ = 0, entry_record_capacity_ = 0,
         first_capacity_ = 0, list_places_capacity_ = 0, entry_starts_capacity_ = 0, list_counts_capacity_ = 0,
         starts_capacity_ = 0, lists_capacity_ = 0;
};

}  // namespace rcsplat
