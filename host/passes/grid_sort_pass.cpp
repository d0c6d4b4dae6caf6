#include "passes/grid_sort_pass.h"

#include <algorithm>

namespace rcsplat {
namespace {
constexpr const char* kProgram = "grid_sort.cl";
}  // namespace

void GridSortPass::build_ahead(GpuContext& gpu) {
  gpu.build_ahead(kProgram);
  ScanPass::build_ahead(gpu);
}

GridSortPass::GridSortPass(GpuContext& gpu)
    : gpu_(gpu),
      scan_(gpu),
      count_(gpu.kernel(kProgram, "count_grid_buckets")),
      scatter_(gpu.kernel(kProgram, "scatter_into_buckets")),
      order_(gpu.kernel(kProgram, "order_within_buckets")),
      gather_(gpu.kernel(kProgram, "gather_grid_items")) {}

void GridSortPass::reserve(cl::Buffer& buffer, size_t& capacity, size_t count, const char* what) {
  if (buffer() && capacity >= count) return;
  capacity = std::max(std::max<size_t>(count, 1), 2 * capacity);
  buffer = gpu_.buffer(CL_MEM_READ_WRITE, capacity * sizeof(cl_uint), what);
}

void GridSortPass::sort(const cl::Buffer& items, uint32_t words, uint32_t count, const PhotonMapParams& grid,
                        const cl::Buffer& sorted, const cl::Buffer& bucket_starts) {
  const size_t buckets = grid.bucket_count;
  // One count more than buckets, left at 0: its scan is the items' total, the last bucket's end.
  reserve(bucket_counts_, count_capacity_, buckets + 1, "photon grid sort");
  reserve(bucket_fill_, fill_capacity_, buckets, "photon grid sort");
  reserve(item_bucket_, item_capacity_, count, "photon grid sort");
  reserve(order_buffer_, order_capacity_, count, "photon grid sort");
  cl::CommandQueue& queue = gpu_.queue();
  queue.enqueueFillBuffer(bucket_counts_, cl_uint(0), 0, (buckets + 1) * sizeof(cl_uint));
  queue.enqueueFillBuffer(bucket_fill_, cl_uint(0), 0, std::max<size_t>(buckets, 1) * sizeof(cl_uint));
  const size_t group = gpu_.groups().per_item;
  count_.set_buffer<cl_float>("items", items)
      .set("words", cl_uint(words))
      .set("count", cl_uint(count))
      .set("grid", grid)
      .set_buffer<cl_uint>("item_bucket", item_bucket_)
      .set_buffer<cl_uint>("bucket_counts", bucket_counts_);
  count_.launch(count, group);
  scan_.exclusive(bucket_counts_, uint32_t(buckets + 1), bucket_starts);
  scatter_.set_buffer<cl_uint>("item_bucket", item_bucket_)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("bucket_starts", bucket_starts)
      .set_buffer<cl_uint>("bucket_fill", bucket_fill_)
      .set_buffer<cl_uint>("order", order_buffer_);
  scatter_.launch(count, group);
  order_.set_buffer<cl_uint>("bucket_starts", bucket_starts)
      .set("bucket_count", cl_uint(buckets))
      .set_buffer<cl_uint>("order", order_buffer_);
  order_.launch(buckets, group);
  gather_.set_buffer<cl_uint>("items", items)
      .set("words", cl_uint(words))
      .set_buffer<cl_uint>("order", order_buffer_)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("sorted", sorted);
  gather_.launch(size_t(count) * words, group);
}

}  // namespace rcsplat
