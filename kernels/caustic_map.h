// The caustic map's lookup (kernels/caustic_map.cl), for the kernels that read it: the pixels' and the glossy pass's.
#ifndef RCSPLAT_CAUSTIC_MAP_H
#define RCSPLAT_CAUSTIC_MAP_H
#include "photon_map.h"
#include "sampling.h"

// The map as the kernels take it: its photons sorted by bucket, the buckets' first photons, the grid (photon_count 0:
// no map, nothing to add).
#define CAUSTIC_MAP_ARGS \
  __global const PhotonHit *caustic_photons, __global const uint *caustic_buckets, PhotonMapParams caustic_grid
#define CAUSTIC_MAP caustic_photons, caustic_buckets, caustic_grid

// Adds to *sum the incident flux of the photons of `bucket` that lie in the disc of squared radius r2 about x, on a
// surface facing ng's way (in_disc).
inline void add_bucket_in_disc(__global const PhotonHit* photons, __global const uint* buckets, uint bucket, float3 x,
                               float3 ng, float r2, float half_thickness, float3* sum) {
  for (uint j = buckets[bucket]; j < buckets[bucket + 1u]; ++j) {
    float3 d = vload3(0, photons[j].position) - x;
    if (in_disc(d, vload3(0, photons[j].normal), ng, r2, half_thickness)) *sum += vload3(0, photons[j].incident);
  }
}

// The caustic irradiance at x on a surface facing ng's way: the photons of the 3 x 3 x 3 cells about x (cells are at
// least a radius wide) that lie in the disc of radius caustic_grid.radius about x, their incident flux over pi r^2.
inline float3 caustic_irradiance(CAUSTIC_MAP_ARGS, float3 x, float3 ng) {
  if (caustic_grid.photon_count == 0u) return (float3)(0.0f);
  float r = caustic_grid.radius, r2 = r * r, half_thickness = PHOTON_DISC_HALF_THICKNESS * r;
  float3 o = vload3(0, caustic_grid.grid_origin), sum = (float3)(0.0f);
  int cx = photon_cell(x.x, o.x, caustic_grid.cell_size), cy = photon_cell(x.y, o.y, caustic_grid.cell_size),
      cz = photon_cell(x.z, o.z, caustic_grid.cell_size);
  uint visited[27];
  uint visited_count = 0;
  for (int c = 0; c < 27; ++c) {
    uint bucket = photon_bucket(cx + c % 3 - 1, cy + (c / 3) % 3 - 1, cz + c / 9 - 1, caustic_grid.bucket_count);
    if (first_visit(bucket, visited, &visited_count))
      add_bucket_in_disc(caustic_photons, caustic_buckets, bucket, x, ng, r2, half_thickness, &sum);
  }
  return finite_or_zero(sum / (RC_PI * r2));
}

// One level of a map in levels (CausticMapLevel), whose cells are at least twice its radius wide: the disc about x then
// meets only the 2 x 2 x 2 cells nearest x, the cell holding it and, along each axis, the one beside its nearer face.
inline float3 caustic_level_irradiance(__global const PhotonHit* photons, __global const uint* buckets,
                                       PhotonMapParams grid, float3 x, float3 ng) {
  const float r = grid.radius, r2 = r * r, half_thickness = PHOTON_DISC_HALF_THICKNESS * r;
  const float3 o = vload3(0, grid.grid_origin);
  const int cx = photon_cell(x.x, o.x, grid.cell_size), cy = photon_cell(x.y, o.y, grid.cell_size),
            cz = photon_cell(x.z, o.z, grid.cell_size);
  // Toward the nearer face: the cell's centre lies at (c + 0.5) cells.
  const int sx = x.x - o.x < ((float)cx + 0.5f) * grid.cell_size ? -1 : 1;
  const int sy = x.y - o.y < ((float)cy + 0.5f) * grid.cell_size ? -1 : 1;
  const int sz = x.z - o.z < ((float)cz + 0.5f) * grid.cell_size ? -1 : 1;
  uint visited[8];
  uint visited_count = 0;
  float3 sum = (float3)(0.0f);
  for (int c = 0; c < 8; ++c) {
    const uint bucket = photon_bucket(cx + (c & 1) * sx, cy + ((c >> 1) & 1) * sy, cz + (c >> 2) * sz, grid.bucket_count);
    if (first_visit(bucket, visited, &visited_count))
      add_bucket_in_disc(photons, buckets, bucket, x, ng, r2, half_thickness, &sum);
  }
  return sum / (RC_PI * r2);
}

// The irradiance of a map in levels (CausticMapLevel, the glass caustic map) over a footprint of this width about x on
// its surface (0: at x alone): each level's photons spread over its own radius, summed. A level whose radius is below
// the footprint (its discs would fall between neighbouring samples' points) is read at four points of a rotated grid
// across it and averaged, so that a pixel takes a focus smaller than itself by its area rather than by where its one
// point falls. A level whose reach x lies outside costs nothing more.
inline float3 caustic_levels_irradiance(__global const PhotonHit* photons, __global const uint* buckets,
                                        __global const CausticMapLevel* levels, float3 x, float3 ng,
                                        float footprint) {
  float3 t, b;
  tangent_frame(ng, &t, &b);
  float3 sum = (float3)(0.0f);
  for (uint j = 0u; j < GLASS_CAUSTIC_LEVELS; ++j) {
    const CausticMapLevel level = levels[j];
    const float r = level.grid.radius;
    const float3 lo = vload3(0, level.reach_min) - (float3)(footprint), hi = vload3(0, level.reach_max) + (float3)(footprint);
    if (level.grid.photon_count == 0u || !all(x >= lo) || !all(x <= hi)) continue;
    __global const PhotonHit* mine = photons + level.first_photon;
    __global const uint* my_buckets = buckets + level.first_bucket;
    if (!(r < footprint)) {
      sum += caustic_level_irradiance(mine, my_buckets, level.grid, x, ng);
      continue;
    }
    // The rotated grid's four points (1/8, 3/8) (3/8, -1/8) ... of the footprint, as the sub-pixels are placed.
    const float s = 0.125f * footprint, l = 0.375f * footprint;
    float3 area = caustic_level_irradiance(mine, my_buckets, level.grid, x + s * t + l * b, ng);
    area += caustic_level_irradiance(mine, my_buckets, level.grid, x + l * t - s * b, ng);
    area += caustic_level_irradiance(mine, my_buckets, level.grid, x - s * t - l * b, ng);
    area += caustic_level_irradiance(mine, my_buckets, level.grid, x - l * t + s * b, ng);
    sum += 0.25f * area;
  }
  return finite_or_zero(sum);
}

#endif
