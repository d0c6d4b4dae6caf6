// The photon map's hashed grid (kernels/photon_map.h), one source for the host, which sorts the photons into buckets
// (host/cache/photon_map.cpp), and the kernels, which look them up.
#ifndef RCSPLAT_PHOTON_GRID_H
#define RCSPLAT_PHOTON_GRID_H
#include "counter_random.h"
#include "host_device.h"

// Map photons and the surface they light face the same way when their normals are closer than 60 degrees: this keeps
// the two sides of a wall, and a floor and the wall it meets, apart.
#define PHOTON_MIN_NORMAL_COSINE 0.5f

// A density estimate counts the photons within the radius r that also lie within this fraction of r of the tangent
// plane (a disc of half-thickness r / 5, Jensen's disc compression): a step, a moulding or a ledge facing the same way
// a little above or below is not the surface the estimate is of. Since estimates divide by the facing area the disc
// really holds (the surface patches), a thin disc no longer loses the curved surfaces it cuts off (columns): on
// Sponza with every material Lambertian, two bounces, map over a path-traced reference, 0.5: 0.983, 0.3: 0.994, 0.2:
// 1.000, 0.1: 1.008 (fewer photons per disc: the estimate's own photon weighs more). RESULTS.md "Photon map, seventh
// step". (Before the patches: 0.5 was the choice, 0.3 cut off columns and raised the block error.)
#define PHOTON_DISC_HALF_THICKNESS 0.2f

// An estimate divides by the area of facing surface in its disc, which the scene's surface patches measure
// (host/cache/photon_map.h surface_patches, at this many per full disc: coarser patches make the area noisier, and
// 1 / area brighter: 16 read Sponza's second bounce 2.6% brighter than 64, 256 0.5% darker). At least this share of
// the full disc counts, so that a few photons on a lone sliver cannot make a spike.
#define PHOTON_PATCHES_PER_DISC 64
#define PHOTON_MIN_AREA_SHARE 0.0625f

// The linear fit of an estimate over its disc (kernels/photon_map.cl density_at_centre) adds this share of a full
// disc's second moment of area to the surface's, so that a narrow strip does not extrapolate its gradient from noise.
#define PHOTON_GRADIENT_RIDGE 0.1f
// A disc that holds fewer photons than this keeps its plain mean, unfitted (the render default's average count).
#define PHOTON_FIT_SUPPORT 64.0f

// The grid cell along one axis holding coordinate x; clamped (a NaN to a bound) so that the conversion is defined
// even for a radius far below the scene's size.
inline int photon_cell(float x, float origin, float cell_size) {
  return (int)rc_fmax(rc_fmin(floor((x - origin) / cell_size), 16777216.0f), -16777216.0f);
}

// The bucket of cell (cx, cy, cz) among bucket_count (a power of two). Different cells may share a bucket: lookups
// test each photon's distance, and visit a bucket once.
inline rc_uint photon_bucket(int cx, int cy, int cz, rc_uint bucket_count) {
  rc_uint h = ((rc_uint)cx * 73856093u) ^ ((rc_uint)cy * 19349663u) ^ ((rc_uint)cz * 83492791u);
  return hash_u32(h) & (bucket_count - 1u);
}

#endif
