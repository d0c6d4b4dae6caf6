#include "passes/grid_sort_pass.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>

#include "kernels/photon_grid.h"
#include "util/error.h"

namespace rcsplat {
void GridSortPass::build_ahead(GpuContext& gpu) {
  gpu.build_ahead(kProgram);
  ScanPass::build_ahead(gpu);
}

GridSortPass::GridSortPass(GpuContext& gpu)
    : gpu_(gpu),
      scan_(gpu),
      count_(gpu.kernel(kProgram, "count_grid_buckets")),
      count_given_(gpu.kernel(kProgram, "count_item_buckets")),
      scatter_(gpu.kernel(kProgram, "scatter_into_buckets")),
      order_(gpu.kernel(kProgram, "order_within_buckets")),
      gather_(gpu.kernel(kProgram, "gather_grid_items")),
      extreme_(gpu.kernel(kProgram, "extreme_positions")),
      keys_(gpu.kernel(kProgram, "coarse_cell_keys")) {}

void GridSortPass::reserve(cl::Buffer& buffer, size_t& capacity, size_t count, const char* what) {
  gpu_.reserve<cl_uint>(buffer, capacity, count, what);
}

void GridSortPass::begin_sort(uint32_t count, size_t buckets) {
  reserve(bucket_counts_, count_capacity_, buckets + 1, "grid sort");
  reserve(bucket_fill_, fill_capacity_, buckets, "grid sort");
  reserve(order_buffer_, order_capacity_, count, "grid sort");
  cl::CommandQueue& queue = gpu_.queue();
  queue.enqueueFillBuffer(bucket_counts_, cl_uint(0), 0, (buckets + 1) * sizeof(cl_uint));
  queue.enqueueFillBuffer(bucket_fill_, cl_uint(0), 0, std::max<size_t>(buckets, 1) * sizeof(cl_uint));
}

void GridSortPass::scatter_in_order(const cl::Buffer& item_bucket, uint32_t count, size_t buckets,
                                    const cl::Buffer& bucket_starts) {
  const size_t group = gpu_.groups().per_item;
  scan_.exclusive(bucket_counts_, uint32_t(buckets + 1), bucket_starts);
  scatter_.set_buffer<cl_uint>("item_bucket", item_bucket)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("bucket_starts", bucket_starts)
      .set_buffer<cl_uint>("bucket_fill", bucket_fill_)
      .set_buffer<cl_uint>("order", order_buffer_);
  scatter_.launch(count, group);
  order_.set_buffer<cl_uint>("bucket_starts", bucket_starts)
      .set("bucket_count", cl_uint(buckets))
      .set_buffer<cl_uint>("order", order_buffer_);
  order_.launch(buckets, group);
}

void GridSortPass::sort(const cl::Buffer& items, uint32_t words, uint32_t count, const PhotonMapParams& grid,
                        const cl::Buffer& sorted, const cl::Buffer& bucket_starts) {
  const size_t buckets = grid.bucket_count;
  begin_sort(count, buckets);
  reserve(item_bucket_, item_capacity_, count, "grid sort");
  const size_t group = gpu_.groups().per_item;
  count_.set_buffer<cl_float>("items", items)
      .set("words", cl_uint(words))
      .set("count", cl_uint(count))
      .set("grid", grid)
      .set_buffer<cl_uint>("item_bucket", item_bucket_)
      .set_buffer<cl_uint>("bucket_counts", bucket_counts_);
  count_.launch(count, group);
  scatter_in_order(item_bucket_, count, buckets, bucket_starts);
  gather_.set_buffer<cl_uint>("items", items)
      .set("words", cl_uint(words))
      .set_buffer<cl_uint>("order", order_buffer_)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("sorted", sorted);
  gather_.launch(size_t(count) * words, group);
}

const cl::Buffer& GridSortPass::order_by_bucket(const cl::Buffer& item_bucket, uint32_t count, uint32_t buckets,
                                                const cl::Buffer& bucket_starts) {
  begin_sort(count, buckets);
  count_given_.set_buffer<cl_uint>("item_bucket", item_bucket)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("bucket_counts", bucket_counts_);
  count_given_.launch(count, gpu_.groups().per_item);
  scatter_in_order(item_bucket, count, buckets, bucket_starts);
  return order_buffer_;
}

void GridSortPass::extreme_corner(const cl::Buffer& items, uint32_t words, uint32_t count, bool highest,
                                  size_t slot) {
  if (extreme_.fitted_group(LOWEST_GROUP) != LOWEST_GROUP)
    throw Error("grid_sort.cl: the device runs at most " + std::to_string(extreme_.fitted_group(LOWEST_GROUP)) +
                " work items a group; the grid's corner needs " + std::to_string(LOWEST_GROUP));
  // Each launch leaves one float4 a group: the first reads the items, the next the last one's output.
  const size_t first_groups = (size_t(count) + LOWEST_GROUP - 1) / LOWEST_GROUP;
  gpu_.reserve<cl_float4>(lowest_a_, lowest_a_capacity_, first_groups, "photon grid sort");
  gpu_.reserve<cl_float4>(lowest_b_, lowest_b_capacity_, first_groups, "photon grid sort");
  if (!corners_()) corners_ = gpu_.buffer(CL_MEM_READ_WRITE, 2 * sizeof(cl_float4), "photon grid sort");
  cl::Buffer in = items, out = lowest_a_, spare = lowest_b_;
  uint32_t in_words = words;
  for (size_t n = count;;) {
    const size_t groups = (n + LOWEST_GROUP - 1) / LOWEST_GROUP;
    extreme_.set_buffer<cl_float>("items", in)
        .set("words", cl_uint(in_words))
        .set("count", cl_uint(n))
        .set("highest", cl_uint(highest ? 1 : 0))
        .set_buffer<cl_float4>("extreme", out);
    extreme_.launch(groups * LOWEST_GROUP, LOWEST_GROUP);
    if (groups == 1) break;
    in = out;
    std::swap(out, spare);
    in_words = 4;
    n = groups;
  }
  gpu_.queue().enqueueCopyBuffer(out, corners_, 0, slot * sizeof(cl_float4), sizeof(cl_float4));
}

PhotonMapParams GridSortPass::grid_params(const cl::Buffer& items, uint32_t words, uint32_t count, float radius) {
  std::array<float, 3> lowest = {INFINITY, INFINITY, INFINITY};
  if (count) {
    extreme_corner(items, words, count, false, 0);
    const cl_float4 corner = gpu_.download<cl_float4>(corners_, 1)[0];
    for (int a = 0; a < 3; ++a) lowest[a] = corner.s[a];
  }
  return photon_grid_params(count, lowest, radius);
}

void GridSortPass::locality_order(const cl::Buffer& items, uint32_t words, uint32_t count, const PhotonMapParams& grid,
                                  const cl::Buffer& order) {
  if (count == 0) return;
  extreme_corner(items, words, count, false, 0);
  extreme_corner(items, words, count, true, 1);
  const std::vector<cl_float4> corners = gpu_.download<cl_float4>(corners_, 2);
  // Codes of `bits` bits an axis, at most 2 count of them (10 bits at most: 2^30 codes); cells grouped 2^shift a side
  // until the widest axis's span fits.
  int lowest[3];
  uint32_t span = 1;
  for (int a = 0; a < 3; ++a) {
    lowest[a] = photon_cell(corners[0].s[a], grid.grid_origin[a], grid.cell_size);
    const int highest = photon_cell(corners[1].s[a], grid.grid_origin[a], grid.cell_size);
    span = std::max(span, uint32_t(std::max(highest - lowest[a], 0)) + 1);
  }
  const uint32_t bits = std::min(10u, uint32_t(std::bit_width(2 * uint64_t(count)) - 1) / 3);
  const uint32_t side = 1u << bits;
  uint32_t shift = 0;
  while ((uint64_t(span) - 1) >> shift >= side) ++shift;
  const uint32_t keys = side * side * side;
  reserve(item_bucket_, item_capacity_, count, "grid sort");
  keys_.set_buffer<cl_float>("items", items)
      .set("words", cl_uint(words))
      .set("count", cl_uint(count))
      .set("grid", grid)
      .set("lowest_x", cl_int(lowest[0]))
      .set("lowest_y", cl_int(lowest[1]))
      .set("lowest_z", cl_int(lowest[2]))
      .set("shift", cl_uint(shift))
      .set("side", cl_uint(side))
      .set_buffer<cl_uint>("item_key", item_bucket_);
  keys_.launch(count, gpu_.groups().per_item);
  reserve(key_starts_, key_starts_capacity_, size_t(keys) + 1, "grid sort");
  const cl::Buffer& sorted = order_by_bucket(item_bucket_, count, keys, key_starts_);
  gpu_.queue().enqueueCopyBuffer(sorted, order, 0, 0, size_t(count) * sizeof(cl_uint));
}

}  // namespace rcsplat
