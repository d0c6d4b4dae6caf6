// The photon map's hashed grids sorted on the device (kernels/grid_sort.cl): the same grid as the host's
// sort_into_grid (cache/photon_map.h), bit for bit, without the items leaving the device; and items whose buckets
// are given put in bucket order (the world-record grid's entries, passes/world_record_grid_pass.h). Owns its scratch
// buffers (each item's bucket, the buckets' counts and fill, the sorted order), kept for the next sort.
#pragma once
#include <cstdint>

#include "cl/gpu_context.h"
#include "cache/photon_map.h"
#include "passes/scan_pass.h"

namespace rcsplat {

class GridSortPass {
 public:
  explicit GridSortPass(GpuContext& gpu);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // `count` items of `words` 32-bit words each in `items`, the first three their position (PhotonHit, SurfacePatch),
  // into `sorted` (as many items) in the order of grid's buckets, the items' own order within a bucket, and
  // `bucket_starts` (grid.bucket_count + 1 entries: bucket h holds sorted items [starts[h], starts[h + 1])). The grid's
  // parameters come from photon_grid_params.
  void sort(const cl::Buffer& items, uint32_t words, uint32_t count, const PhotonMapParams& grid,
            const cl::Buffer& sorted, const cl::Buffer& bucket_starts);
  // Items whose buckets are given (item_bucket: `count` of them, each below `buckets`) put in bucket order, the items'
  // own order within a bucket: the returned buffer's k-th uint is the item at place k (valid until the next sort), and
  // `bucket_starts` (buckets + 1 entries) where each bucket's places start.
  const cl::Buffer& order_by_bucket(const cl::Buffer& item_bucket, uint32_t count, uint32_t buckets,
                                    const cl::Buffer& bucket_starts);
  // photon_grid_params of the items in `items` (as sort's), their lowest corner found on the device: 16 bytes read.
  PhotonMapParams grid_params(const cl::Buffer& items, uint32_t words, uint32_t count, float radius);
  // An order of the items (as sort's) that keeps neighbours in space together, into `order` (count uints: the item
  // at place k): by the Morton code of their cells in `grid`, coarsened until there are at most twice as many codes as
  // items, and the items' own order within a code (a counting sort, as order_by_bucket). Their lowest and highest
  // corners are found on the device: 32 bytes read. For work whose result does not depend on its order (the photon
  // estimates), only on how much of its neighbourhood it shares with work running beside it.
  void locality_order(const cl::Buffer& items, uint32_t words, uint32_t count, const PhotonMapParams& grid,
                      const cl::Buffer& order);

 private:
  static constexpr const char* kProgram = "grid_sort.cl";  // its kernels' file
  // The buckets' counts zeroed (and one more, left at 0: its scan is the items' total) and the order's buffer grown.
  void begin_sort(uint32_t count, size_t buckets);
  // From the counts: scanned into bucket_starts, the items scattered into their buckets and ordered within them.
  void scatter_in_order(const cl::Buffer& item_bucket, uint32_t count, size_t buckets, const cl::Buffer& bucket_starts);
  // `buffer` holding at least `count` uints (GpuContext::reserve).
  void reserve(cl::Buffer& buffer, size_t& capacity, size_t count, const char* what);
  // The items' lowest (or highest) corner reduced on the device into corners_[slot] (a float4); nothing read.
  void extreme_corner(const cl::Buffer& items, uint32_t words, uint32_t count, bool highest, size_t slot);

  GpuContext& gpu_;
  ScanPass scan_;
  NamedKernel count_, count_given_, scatter_, order_, gather_, extreme_, keys_;
  cl::Buffer item_bucket_, bucket_counts_, bucket_fill_, order_buffer_, lowest_a_, lowest_b_, corners_;
  cl::Buffer key_starts_;  // locality_order's starts of each code's items
  size_t item_capacity_ = 0, order_capacity_ = 0, count_capacity_ = 0, fill_capacity_ = 0, lowest_a_capacity_ = 0,
         lowest_b_capacity_ = 0,
         key_starts_capacity_ = 0;
};

}  // namespace rcsplat
