// The splat's records found by position in the world, not by pixel: a glossy pixel's reflection lands where no pixel
// of the splat may be, yet a record placed for a pixel there holds the irradiance the reflection needs
// (kernels/glossy.cl, docs/ALGORITHM.md section 8). The grid is built on the device (kernels/world_record_grid.cl); the
// interpolation is the splat's, record for record: Ward's weight, record_reaches, the gradients' extrapolation and
// the splat's bound on it (kernels/splat.cl), so that a point read both ways agrees (tests/world_records_test.cpp).
#ifndef RCSPLAT_WORLD_RECORDS_H
#define RCSPLAT_WORLD_RECORDS_H
#include "cache_math.h"
#include "photon_grid.h"
#include "sampling.h"

#define WORLD_RECORD_ARGS                                                                           \
  __global const CacheRecord *world_records, __global const uint *world_record_starts,              \
      __global const uint *world_record_lists, WorldRecordParams world_grid
#define WORLD_RECORDS world_records, world_record_starts, world_record_lists, world_grid

// The irradiance the records interpolate at p (shading normal n), sum w E_k(p) / sum w over the records that reach p
// (record_reaches); *weight: sum w, 0 where no record reaches p (the result is then 0).
inline float3 world_cached_irradiance(WORLD_RECORD_ARGS, float3 p, float3 n, float* weight) {
  *weight = 0.0f;
  if (world_grid.record_count == 0u) return (float3)(0.0f);
  float3 o = vload3(0, world_grid.grid_origin);
  uint bucket = photon_bucket(photon_cell(p.x, o.x, world_grid.cell_size), photon_cell(p.y, o.y, world_grid.cell_size),
                              photon_cell(p.z, o.z, world_grid.cell_size), world_grid.bucket_count);
  float3 sum = (float3)(0.0f);
  float weights = 0.0f;
  for (uint j = world_record_starts[bucket]; j < world_record_starts[bucket + 1u]; ++j) {
    __global const CacheRecord* rec = world_records + world_record_lists[j];
    float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal), tk, bk;
    float radius = rec->radius;
    float w = ward_weight(p, n, pk, nk, radius);
    if (!(w * world_grid.accuracy > 1.0f)) continue;  // the cheap part of record_reaches first
    tangent_frame(nk, &tk, &bk);
    if (!record_reaches(rec, tk, bk, w, world_grid.accuracy, p, n, pk, nk, radius)) continue;
    sum += w * fmin(extrapolated_irradiance(rec, p, n), (float3)(world_grid.irradiance_scale));
    weights += w;
  }
  *weight = weights;
  return weights > 0.0f ? finite_or_zero(sum / weights) : (float3)(0.0f);
}

#endif
