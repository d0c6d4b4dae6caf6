// Which cells of the world-record grid (kernels/world_records.h) a record's reach sphere meets: one source for the
// host's build (tests/reference/world_record_grid.cpp) and the device's (kernels/world_record_grid.cl), so that both list
// the same records in the same buckets, bit for bit.
#ifndef RCSPLAT_WORLD_RECORD_CELLS_H
#define RCSPLAT_WORLD_RECORD_CELLS_H
#include "photon_grid.h"

// The cells along `axis` that a sphere about `centre` of radius `reach` may meet: first .. last.
inline void reach_cell_span(float centre, float reach, float origin, float cell_size, int* first, int* last) {
  *first = photon_cell(centre - reach, origin, cell_size);
  *last = photon_cell(centre + reach, origin, cell_size);
}

// The squared distance along one axis from `centre` to cell c's slab [origin + c size, + size]: 0 inside it.
inline float cell_gap_squared(float centre, int c, float origin, float cell_size) {
  const float b0 = origin + (float)c * cell_size, b1 = b0 + cell_size;
  const float d = rc_fmax(rc_fmax(b0 - centre, 0.0f), centre - b1);
  return d * d;
}

// Whether the sphere meets cell (x, y, z) (not only its bounding cube): the distance from its centre to the cell's
// box within the reach, and a hair more (the lookups round their cells their own way).
inline bool reach_meets_cell(float px, float py, float pz, float reach, float ox, float oy, float oz, float cell_size,
                             int x, int y, int z) {
  float d2 = cell_gap_squared(px, x, ox, cell_size);
  d2 += cell_gap_squared(py, y, oy, cell_size);
  d2 += cell_gap_squared(pz, z, oz, cell_size);
  return !(d2 > 1.002f * reach * reach);
}

#endif
