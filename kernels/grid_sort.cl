// The photon map's hashed grids sorted on the device (host/passes/grid_sort_pass.h): items (photons, surface
// patches) of `words` 32-bit words each, the first three their position, put in bucket order the way the host's
// stable counting sort does (host/cache/photon_map.cpp sort_into_grid), bit for bit: each item's bucket and each
// bucket's count, the counts scanned into the buckets' starts (kernels/scan.cl), the items' numbers scattered into
// their buckets, each bucket's numbers put back in the items' order, and the items gathered in that order. The same
// steps order items whose buckets are given (count_item_buckets: the world-record grid's entries).
#include "shared_types.h"
#include "photon_grid.h"

__kernel void count_grid_buckets(__global const float* items, uint words, uint count, PhotonMapParams grid,
                                 __global uint* item_bucket, __global uint* bucket_counts) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  __global const float* position = items + i * words;
  int cell[3];
  for (int a = 0; a < 3; ++a) cell[a] = photon_cell(position[a], grid.grid_origin[a], grid.cell_size);
  const uint bucket = photon_bucket(cell[0], cell[1], cell[2], grid.bucket_count);
  item_bucket[i] = bucket;
  atomic_inc(&bucket_counts[bucket]);
}

// The buckets' counts of items whose buckets are given (the world-record grid's entries: kernels/world_record_grid.cl).
__kernel void count_item_buckets(__global const uint* item_bucket, uint count, __global uint* bucket_counts) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  atomic_inc(&bucket_counts[item_bucket[i]]);
}

// Places within a bucket are handed out in whatever order work-items run: order_within_buckets restores the items'.
__kernel void scatter_into_buckets(__global const uint* item_bucket, uint count, __global const uint* bucket_starts,
                                   __global uint* bucket_fill, __global uint* order) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  const uint bucket = item_bucket[i];
  order[bucket_starts[bucket] + atomic_inc(&bucket_fill[bucket])] = (uint)i;
}

// Sifts range[root] down the max-heap of range[0 .. n).
inline void sift_down(__global uint* range, uint root, uint n) {
  const uint value = range[root];
  for (uint child = 2u * root + 1u; child < n; child = 2u * root + 1u) {
    if (child + 1u < n && range[child + 1u] > range[child]) ++child;
    if (range[child] <= value) break;
    range[root] = range[child];
    root = child;
  }
  range[root] = value;
}

// A bucket holds about one item (twice as many buckets as items); a crowded one (photons focused on a small spot) is
// heap-sorted, in place and in n log n steps, where an insertion sort would take n^2.
__kernel void order_within_buckets(__global const uint* bucket_starts, uint bucket_count, __global uint* order) {
  const size_t bucket = get_global_id(0);
  if (bucket >= bucket_count) return;
  __global uint* range = order + bucket_starts[bucket];
  const uint n = bucket_starts[bucket + 1] - bucket_starts[bucket];
  if (n <= 16u) {
    for (uint i = 1u; i < n; ++i) {
      const uint value = range[i];
      uint j = i;
      for (; j > 0u && range[j - 1u] > value; --j) range[j] = range[j - 1u];
      range[j] = value;
    }
    return;
  }
  for (uint root = n / 2u; root-- > 0u;) sift_down(range, root, n);
  for (uint end = n - 1u; end > 0u; --end) {
    const uint largest = range[0];
    range[0] = range[end];
    range[end] = largest;
    sift_down(range, 0u, end);
  }
}

// A work-item a word: sorted item k is item order[k].
__kernel void gather_grid_items(__global const uint* items, uint words, __global const uint* order, uint count,
                                __global uint* sorted) {
  const size_t w = get_global_id(0);
  if (w >= (size_t)count * words) return;
  const size_t k = w / words;
  sorted[w] = items[(size_t)order[k] * words + w % words];
}

// The lowest coordinate on each axis of each group's LOWEST_GROUP items (xyz; w unused), or with `highest` the
// highest: for the grid's origin, the host's loop of std::min over the items, exactly, as a minimum is in any order;
// and the extent the estimates' order spans. Launched again over its own output (words 4) until one group is left.
__kernel void extreme_positions(__global const float* items, uint words, uint count, uint highest,
                                __global float4* extreme) {
  __local float x[LOWEST_GROUP], y[LOWEST_GROUP], z[LOWEST_GROUP];
  const size_t i = get_global_id(0);
  const uint item = get_local_id(0);
  const float none = highest ? -INFINITY : INFINITY;
  x[item] = i < count ? items[i * words] : none;
  y[item] = i < count ? items[i * words + 1] : none;
  z[item] = i < count ? items[i * words + 2] : none;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint step = LOWEST_GROUP / 2; step > 0; step /= 2) {
    if (item < step) {
      x[item] = highest ? fmax(x[item], x[item + step]) : fmin(x[item], x[item + step]);
      y[item] = highest ? fmax(y[item], y[item + step]) : fmin(y[item], y[item + step]);
      z[item] = highest ? fmax(z[item], z[item + step]) : fmin(z[item], z[item + step]);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (item == 0) extreme[get_group_id(0)] = (float4)(x[0], y[0], z[0], 0.0f);
}

// v's low 10 bits spread to every third bit (bit k to bit 3k).
inline uint spread_to_every_third_bit(uint v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

// Each item's key for an order that keeps neighbours in space together (the photon estimates', PhotonMapPass): its
// grid cell counted from `lowest`, coarsened to 2^shift cells a side, held below `side` (a power of two of at most
// 2^10) and interleaved into a Morton code below side^3.
__kernel void coarse_cell_keys(__global const float* items, uint words, uint count, PhotonMapParams grid,
                               int lowest_x, int lowest_y, int lowest_z, uint shift, uint side,
                               __global uint* item_key) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  __global const float* position = items + i * words;
  const int lowest[3] = {lowest_x, lowest_y, lowest_z};
  uint key = 0u;
  for (int a = 0; a < 3; ++a) {
    const int cell = photon_cell(position[a], grid.grid_origin[a], grid.cell_size) - lowest[a];
    const uint coarse = min((uint)max(cell, 0) >> shift, side - 1u);
    key |= spread_to_every_third_bit(coarse) << a;
  }
  item_key[i] = key;
}
