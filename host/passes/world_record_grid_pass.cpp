#include "passes/world_record_grid_pass.h"

#include <algorithm>
#include <bit>
#include <string>

#include "util/error.h"

namespace rcsplat {
void WorldRecordGridPass::build_ahead(GpuContext& gpu) {
  gpu.build_ahead(kProgram);
  GridSortPass::build_ahead(gpu);
}

WorldRecordGridPass::WorldRecordGridPass(GpuContext& gpu)
    : gpu_(gpu),
      sort_(gpu),
      scan_(gpu),
      measure_(gpu.kernel(kProgram, "measure_world_records")),
      count_digits_(gpu.kernel(kProgram, "count_diameter_digits")),
      choose_digit_(gpu.kernel(kProgram, "choose_diameter_digit")),
      lay_out_(gpu.kernel(kProgram, "lay_out_world_grid")),
      count_cells_(gpu.kernel(kProgram, "count_record_cells")),
      write_cells_(gpu.kernel(kProgram, "write_record_cells")),
      mark_first_(gpu.kernel(kProgram, "mark_first_listings")),
      write_lists_(gpu.kernel(kProgram, "write_record_lists")) {
  extent_ = gpu.buffer(CL_MEM_READ_WRITE, sizeof(WorldRecordExtent), "world record grid");
  bins_ = gpu.buffer(CL_MEM_READ_WRITE, WORLD_RECORD_DIGIT_BINS * sizeof(cl_uint), "world record grid");
  params_ = gpu.buffer(CL_MEM_READ_WRITE, sizeof(WorldRecordParams), "world record grid");
}

void WorldRecordGridPass::reserve(cl::Buffer& buffer, size_t& capacity, size_t count) {
  gpu_.reserve<cl_uint>(buffer, capacity, count, "world record grid");
}

DeviceWorldRecordGrid WorldRecordGridPass::build(const cl::Buffer& records, uint32_t record_count, float accuracy) {
  cl::CommandQueue& queue = gpu_.queue();
  const size_t group = gpu_.groups().per_item;
  // The extent: the lowest corner starts at the top of the ordered bits, every maximum and count at 0.
  queue.enqueueFillBuffer(extent_, cl_uint(0xffffffffu), 0, 3 * sizeof(cl_uint));
  queue.enqueueFillBuffer(extent_, cl_uint(0), 3 * sizeof(cl_uint), sizeof(WorldRecordExtent) - 3 * sizeof(cl_uint));
  queue.enqueueFillBuffer(bins_, cl_uint(0), 0, WORLD_RECORD_DIGIT_BINS * sizeof(cl_uint));
  // The measuring kernels start with the records, their count and the accuracy, then the extent.
  auto bind_records = [&](NamedKernel& kernel) -> NamedKernel& {
    return kernel.set_buffer<CacheRecord>("records", records)
        .set("record_count", cl_uint(record_count))
        .set("accuracy", cl_float(accuracy))
        .set_buffer<WorldRecordExtent>("extent", extent_);
  };
  if (record_count) {
    bind_records(measure_).launch(record_count, group);
    for (uint32_t shift = 24;; shift -= 8) {
      bind_records(count_digits_)
          .set("shift", cl_uint(shift))
          .set_buffer<cl_uint>("bins", bins_);
      count_digits_.launch(record_count, group);
      choose_digit_.set_buffer<WorldRecordExtent>("extent", extent_)
          .set("shift", cl_uint(shift))
          .set_buffer<cl_uint>("bins", bins_);
      choose_digit_.launch(1, 1);
      if (shift == 0) break;
    }
  }
  lay_out_.set_buffer<WorldRecordExtent>("extent", extent_)
      .set("record_count", cl_uint(record_count))
      .set("accuracy", cl_float(accuracy))
      .set_buffer<WorldRecordParams>("params", params_);
  lay_out_.launch(1, 1);
  DeviceWorldRecordGrid grid;
  grid.records = &records;
  grid.bucket_starts = &bucket_starts_;
  grid.record_lists = &record_lists_;

  // Each record's cells, scanned into where its entries go; their total sizes the buckets (as the host's). The grid's
  // parameters and that total come back together.
  reserve(cells_, cells_capacity_, size_t(record_count) + 1);
  reserve(cell_places_, cell_places_capacity_, size_t(record_count) + 1);
  queue.enqueueFillBuffer(cells_, cl_uint(0), size_t(record_count) * sizeof(cl_uint), sizeof(cl_uint));
  if (record_count) {
    count_cells_.set_buffer<CacheRecord>("records", records)
        .set("record_count", cl_uint(record_count))
        .set_buffer<WorldRecordParams>("grid_at", params_)
        .set_buffer<cl_uint>("cells", cells_);
    count_cells_.launch(record_count, group);
  }
  scan_.exclusive(cells_, record_count + 1, cell_places_);
  cl_uint entries = 0;
  queue.enqueueReadBuffer(params_, CL_FALSE, 0, sizeof(WorldRecordParams), &grid.params);
  queue.enqueueReadBuffer(cell_places_, CL_TRUE, size_t(record_count) * sizeof(cl_uint), sizeof(cl_uint), &entries);
  if (grid.params.record_count == 0) {  // nothing listed: the host's empty grid, one bucket, no lists
    gpu_.upload_into(bucket_starts_, starts_capacity_, std::vector<cl_uint>{0, 0}, CL_MEM_READ_WRITE,
                     "world record grid");
    gpu_.upload_into(record_lists_, lists_capacity_, std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, "world record grid");
    return grid;
  }
  // Every listed record meets at least the cell its centre is in; the bound keeps the entries' scans in 32 bits.
  if (entries == 0 || entries > (1u << 30))
    throw Error("world record grid: " + std::to_string(entries) + " cells for " + std::to_string(record_count) +
                " records");
  const uint32_t buckets = uint32_t(std::bit_ceil(std::max<size_t>(2 * size_t(entries), 2)));
  grid.params.bucket_count = buckets;

  reserve(entry_bucket_, entry_bucket_capacity_, entries);
  reserve(entry_record_, entry_record_capacity_, entries);
  write_cells_.set_buffer<CacheRecord>("records", records)
      .set("record_count", cl_uint(record_count))
      .set("grid", grid.params)
      .set_buffer<cl_uint>("places", cell_places_)
      .set_buffer<cl_uint>("entry_bucket", entry_bucket_)
      .set_buffer<cl_uint>("entry_record", entry_record_);
  write_cells_.launch(record_count, group);

  // In bucket order, each bucket's entries in the records' order; a record twice in a bucket kept once.
  reserve(entry_starts_, entry_starts_capacity_, size_t(buckets) + 1);
  const cl::Buffer& order = sort_.order_by_bucket(entry_bucket_, entries, buckets, entry_starts_);
  reserve(first_, first_capacity_, size_t(entries) + 1);
  reserve(list_places_, list_places_capacity_, size_t(entries) + 1);
  queue.enqueueFillBuffer(first_, cl_uint(0), size_t(entries) * sizeof(cl_uint), sizeof(cl_uint));
  mark_first_.set_buffer<cl_uint>("order", order)
      .set_buffer<cl_uint>("entry_bucket", entry_bucket_)
      .set_buffer<cl_uint>("entry_record", entry_record_)
      .set("entry_count", cl_uint(entries))
      .set_buffer<cl_uint>("first", first_);
  mark_first_.launch(entries, group);
  scan_.exclusive(first_, entries + 1, list_places_);
  reserve(record_lists_, lists_capacity_, entries);
  reserve(list_counts_, list_counts_capacity_, size_t(buckets) + 1);
  queue.enqueueFillBuffer(list_counts_, cl_uint(0), 0, (size_t(buckets) + 1) * sizeof(cl_uint));
  write_lists_.set_buffer<cl_uint>("order", order)
      .set_buffer<cl_uint>("entry_bucket", entry_bucket_)
      .set_buffer<cl_uint>("entry_record", entry_record_)
      .set("entry_count", cl_uint(entries))
      .set_buffer<cl_uint>("first", first_)
      .set_buffer<cl_uint>("places", list_places_)
      .set_buffer<cl_uint>("lists", record_lists_)
      .set_buffer<cl_uint>("bucket_counts", list_counts_);
  write_lists_.launch(entries, group);
  reserve(bucket_starts_, starts_capacity_, size_t(buckets) + 1);
  scan_.exclusive(list_counts_, buckets + 1, bucket_starts_);
  return grid;
}

}  // namespace rcsplat
