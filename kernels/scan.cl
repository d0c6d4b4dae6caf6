// Exclusive prefix sums of uints on the device (host/passes/scan_pass.h), the building block of compactions that keep
// their order: a flag per element scanned gives each kept element its place, the same places whatever order work
// items run in (an atomic counter hands them out in the order the device happens to run them).
//
// A work-group scans SCAN_BLOCK elements: each of its SCAN_GROUP items sums SCAN_ITEMS consecutive ones, the group scans
// those sums in local memory (Hillis and Steele: log2(SCAN_GROUP) steps), and each item writes its elements' prefixes.
// The block's total goes to block_sums; the block sums are scanned the same way, and add_block_offsets adds them back.
#include "shared_types.h"

__kernel void scan_blocks(__global const uint* in, uint count, __global uint* out, __global uint* block_sums) {
  __local uint sums[SCAN_GROUP];
  const uint item = get_local_id(0);
  const size_t first = get_group_id(0) * (size_t)SCAN_BLOCK + (size_t)item * SCAN_ITEMS;
  uint values[SCAN_ITEMS], total = 0u;
  for (uint i = 0; i < SCAN_ITEMS; ++i) {
    values[i] = first + i < count ? in[first + i] : 0u;
    total += values[i];
  }
  sums[item] = total;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint step = 1; step < SCAN_GROUP; step *= 2) {
    const uint before = item >= step ? sums[item - step] : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    sums[item] += before;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  uint running = sums[item] - total;  // the items before this one (inclusive scan less its own)
  for (uint i = 0; i < SCAN_ITEMS; ++i) {
    if (first + i < count) out[first + i] = running;
    running += values[i];
  }
  if (item == SCAN_GROUP - 1) block_sums[get_group_id(0)] = sums[item];
}

// out[i] += the scanned sum of the blocks before i's block.
__kernel void add_block_offsets(__global const uint* block_offsets, uint count, __global uint* out) {
  const size_t i = get_global_id(0);
  if (i < count) out[i] += block_offsets[i / SCAN_BLOCK];
}
