// The world-record grid (kernels/world_records.h) built on the device from the records where the splat left them
// (host/passes/world_record_grid_pass.h): the same grid as the host's build_world_record_grid
// (tests/reference/world_record_grid.cpp), bit for bit, without the records coming back. In order:
//   measure_world_records      the kept records' lowest corner and widest sphere, the brightest record;
//   count_diameter_digits,     the median diameter by a radix selection, a byte at a time from the top: each byte's
//   choose_diameter_digit      histogram over the diameters that share the bytes chosen so far, then the byte that
//                              holds the median's rank (an exact order statistic, as the host's nth_element);
//   lay_out_world_grid         the grid's cell and corner, as the host's;
//   count_record_cells,        each record's cells (kernels/world_record_cells.h), scanned into its entries' places
//   write_record_cells         and written as (bucket, record), record by record;
//   (grid_sort.cl)             the entries put in bucket order, each bucket's in the entries' order, which is the
//                              records' order;
//   mark_first_listings,       a record listed twice in one bucket (two of its cells hash there) kept once, and the
//   write_record_lists         buckets' counts scanned into their starts.
#include "shared_types.h"
#include "cache_math.h"
#include "world_record_cells.h"

// A float's order as a uint's (negative floats reversed below the positive ones): minima and maxima by atomics.
inline uint ordered_bits(float f) {
  const uint b = as_uint(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
inline float from_ordered_bits(uint o) { return as_float((o & 0x80000000u) ? (o & 0x7fffffffu) : ~o); }

// The reach a record is listed by, and whether it is listed at all (the host's test: finite, positive, at a finite
// position).
inline bool listed_reach(__global const CacheRecord* r, float accuracy, float* reach) {
  *reach = accuracy * r->radius;
  return isfinite(*reach) && *reach > 0.0f && isfinite(r->position[0]) && isfinite(r->position[1]) &&
         isfinite(r->position[2]);
}

// A work-group folds its records into local minima and maxima, then into the frame's with one atomic each (extent
// starts with lowest all ones, the rest 0).
__kernel void measure_world_records(__global const CacheRecord* records, uint record_count, float accuracy,
                                    __global WorldRecordExtent* extent) {
  __local uint lowest[3], widest, largest, kept;
  const size_t i = get_global_id(0);
  if (get_local_id(0) == 0) {
    lowest[0] = lowest[1] = lowest[2] = 0xffffffffu;
    widest = largest = kept = 0u;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (i < record_count) {
    __global const CacheRecord* r = records + i;
    const float3 e = vload3(0, r->irradiance);
    atomic_max(&largest, as_uint(fmax(fmax(e.x, e.y), fmax(e.z, 0.0f))));  // as the splat's max_record_irradiance
    float reach;
    if (listed_reach(r, accuracy, &reach)) {
      for (int a = 0; a < 3; ++a) atomic_min(&lowest[a], ordered_bits(r->position[a] - reach));
      atomic_max(&widest, as_uint(2.0f * reach));
      atomic_inc(&kept);
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0) {
    for (int a = 0; a < 3; ++a) atomic_min(&extent->lowest[a], lowest[a]);
    atomic_max(&extent->widest_bits, widest);
    atomic_max(&extent->largest_bits, largest);
    if (kept) atomic_add(&extent->kept, kept);
  }
}

// The histogram of byte `shift / 8` of the kept diameters whose higher bytes are the median's so far (bins start at
// 0; choose_diameter_digit clears them after reading).
__kernel void count_diameter_digits(__global const CacheRecord* records, uint record_count, float accuracy,
                                    __global const WorldRecordExtent* extent, uint shift, __global uint* bins) {
  __local uint local_bins[WORLD_RECORD_DIGIT_BINS];
  const size_t i = get_global_id(0);
  for (uint b = get_local_id(0); b < WORLD_RECORD_DIGIT_BINS; b += get_local_size(0)) local_bins[b] = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  float reach;
  if (i < record_count && listed_reach(records + i, accuracy, &reach)) {
    const uint bits = as_uint(2.0f * reach);
    const uint higher = shift >= 24u ? 0u : 0xffffffffu << (shift + 8u);
    if ((bits & higher) == (extent->median_bits & higher)) atomic_inc(&local_bins[(bits >> shift) & 0xffu]);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint b = get_local_id(0); b < WORLD_RECORD_DIGIT_BINS; b += get_local_size(0))
    if (local_bins[b]) atomic_add(&bins[b], local_bins[b]);
}

// One work item: the byte whose bin holds the median's rank, added to the median's bits; the bins cleared.
__kernel void choose_diameter_digit(__global WorldRecordExtent* extent, uint shift, __global uint* bins) {
  if (get_global_id(0) != 0) return;
  if (shift >= 24u) {
    extent->median_bits = 0u;
    extent->median_rank = extent->kept / 2u;
  }
  uint rank = extent->median_rank, digit = 0u;
  for (; digit + 1u < WORLD_RECORD_DIGIT_BINS && rank >= bins[digit]; ++digit) rank -= bins[digit];
  extent->median_bits |= digit << shift;
  extent->median_rank = rank;
  for (uint b = 0; b < WORLD_RECORD_DIGIT_BINS; ++b) bins[b] = 0u;
}

// One work item: the grid's parameters as the host lays them out (bucket_count is the host's, once it knows the
// entries); record_count 0 where no record is listed.
__kernel void lay_out_world_grid(__global const WorldRecordExtent* extent, uint record_count, float accuracy,
                                 __global WorldRecordParams* params) {
  if (get_global_id(0) != 0) return;
  WorldRecordParams p;
  p.accuracy = accuracy;
  p.irradiance_scale = fixed_point_irradiance_scale(as_float(extent->largest_bits), accuracy);
  p.bucket_count = 1u;
  p.record_count = 0u;
  p.cell_size = 0.0f;
  for (int a = 0; a < 3; ++a) p.grid_origin[a] = 0.0f;
  if (extent->kept) {
    const float median = as_float(extent->median_bits), widest = as_float(extent->widest_bits);
    const float cell = fmax(median, widest / 8.0f);
    p.cell_size = cell;
    for (int a = 0; a < 3; ++a) p.grid_origin[a] = from_ordered_bits(extent->lowest[a]) - cell;
    p.record_count = record_count;
  }
  *params = p;
}

// Visits each cell record r's reach sphere meets, in the host's order (z, then y, then x).
#define FOR_EACH_RECORD_CELL(r, reach, p, BODY)                                                                     \
  {                                                                                                                 \
    int c0[3], c1[3];                                                                                               \
    for (int a = 0; a < 3; ++a) reach_cell_span(r->position[a], reach, p.grid_origin[a], p.cell_size, &c0[a], &c1[a]); \
    for (int z = c0[2]; z <= c1[2]; ++z)                                                                            \
      for (int y = c0[1]; y <= c1[1]; ++y)                                                                          \
        for (int x = c0[0]; x <= c1[0]; ++x)                                                                        \
          if (reach_meets_cell(r->position[0], r->position[1], r->position[2], reach, p.grid_origin[0],             \
                               p.grid_origin[1], p.grid_origin[2], p.cell_size, x, y, z)) {                         \
            BODY                                                                                                    \
          }                                                                                                         \
  }

// cells[i]: the cells record i is listed in (0 for a record not listed). The grid is read where lay_out_world_grid
// wrote it, so that the host reads it back with the cells' total, in one wait.
__kernel void count_record_cells(__global const CacheRecord* records, uint record_count,
                                 __global const WorldRecordParams* grid_at, __global uint* cells) {
  const size_t i = get_global_id(0);
  if (i >= record_count) return;
  const WorldRecordParams grid = *grid_at;
  __global const CacheRecord* r = records + i;
  float reach;
  uint count = 0u;
  if (listed_reach(r, grid.accuracy, &reach)) FOR_EACH_RECORD_CELL(r, reach, grid, ++count;)
  cells[i] = count;
}

// Record i's entries from places[i] on: each cell's bucket and the record.
__kernel void write_record_cells(__global const CacheRecord* records, uint record_count, WorldRecordParams grid,
                                 __global const uint* places, __global uint* entry_bucket,
                                 __global uint* entry_record) {
  const size_t i = get_global_id(0);
  if (i >= record_count) return;
  __global const CacheRecord* r = records + i;
  float reach;
  uint k = places[i];
  if (listed_reach(r, grid.accuracy, &reach))
    FOR_EACH_RECORD_CELL(r, reach, grid, {
      entry_bucket[k] = photon_bucket(x, y, z, grid.bucket_count);
      entry_record[k] = (uint)i;
      ++k;
    })
}

// first[k] = 1 where sorted entry k is the first of its record in its bucket (order[k]: the entry at place k).
__kernel void mark_first_listings(__global const uint* order, __global const uint* entry_bucket,
                                  __global const uint* entry_record, uint entry_count, __global uint* first) {
  const size_t k = get_global_id(0);
  if (k >= entry_count) return;
  const uint e = order[k];
  first[k] = k == 0 || entry_bucket[order[k - 1]] != entry_bucket[e] || entry_record[order[k - 1]] != entry_record[e]
                 ? 1u
                 : 0u;
}

// Each first listing at its place in the lists, and counted in its bucket.
__kernel void write_record_lists(__global const uint* order, __global const uint* entry_bucket,
                                 __global const uint* entry_record, uint entry_count, __global const uint* first,
                                 __global const uint* places, __global uint* lists, __global uint* bucket_counts) {
  const size_t k = get_global_id(0);
  if (k >= entry_count || !first[k]) return;
  const uint e = order[k];
  lists[places[k]] = entry_record[e];
  atomic_inc(&bucket_counts[entry_bucket[e]]);
}
