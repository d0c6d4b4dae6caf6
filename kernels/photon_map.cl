// The photon map's per-photon radiance estimates (kernels/photon_map.h), and the lookup on its own for tests.
#include "photon_map.h"
#include "sampling.h"

// Reflected radiance at the lookup grid's photon i: the reflected flux of every photon (the `all` grid) within
// all_grid.radius and PHOTON_DISC_HALF_THICKNESS r of the tangent plane on a surface facing the same way, over pi
// (Lambertian) times the disc's area pi r^2. The 3 x 3 x 3 cells around the point hold every such photon (cells are at
// least r wide).
// map_shallow: the same over the photons of landings below shallow_landings (PhotonMapGrids::shallow_landings).
__kernel void estimate_photon_radiance(__global const PhotonHit* all_photons, __global const uint* all_buckets,
                                       PhotonMapParams all_grid, __global const PhotonHit* map_photons,
                                       PhotonMapParams map, int shallow_landings, __global float4* map_radiance,
                                       __global float4* map_shallow) {
  uint i = get_global_id(0);
  if (i >= map.photon_count) return;
  float3 x = vload3(0, map_photons[i].position), n = vload3(0, map_photons[i].normal);
  int cx = photon_cell(x.x, all_grid.grid_origin[0], all_grid.cell_size);
  int cy = photon_cell(x.y, all_grid.grid_origin[1], all_grid.cell_size);
  int cz = photon_cell(x.z, all_grid.grid_origin[2], all_grid.cell_size);
  uint visited[27];
  uint visited_count = 0;
  float r2 = all_grid.radius * all_grid.radius, half_thickness = PHOTON_DISC_HALF_THICKNESS * all_grid.radius;
  float3 flux = (float3)(0.0f), shallow = (float3)(0.0f);
  for (int c = 0; c < 27; ++c) {
    uint bucket = photon_bucket(cx + c % 3 - 1, cy + (c / 3) % 3 - 1, cz + c / 9 - 1, all_grid.bucket_count);
    bool seen = false;
    for (uint v = 0; v < visited_count; ++v) seen = seen || visited[v] == bucket;
    if (seen) continue;
    visited[visited_count++] = bucket;
    for (uint j = all_buckets[bucket]; j < all_buckets[bucket + 1u]; ++j) {
      float3 d = vload3(0, all_photons[j].position) - x;
      if (dot(d, d) < r2 && fabs(dot(d, n)) < half_thickness &&
          dot(vload3(0, all_photons[j].normal), n) > PHOTON_MIN_NORMAL_COSINE) {
        float3 f = vload3(0, all_photons[j].flux);
        flux += f;
        if (all_photons[j].landing < shallow_landings) shallow += f;
      }
    }
  }
  map_radiance[i] = (float4)(finite_or_zero(flux / (RC_PI * RC_PI * r2)), 0.0f);
  map_shallow[i] = (float4)(finite_or_zero(shallow / (RC_PI * RC_PI * r2)), 0.0f);
}

// photon_map_radiance at query points (float4: xyz) with their normals, for tests.
__kernel void look_up_photon_radiance(PHOTON_MAP_ARGS, __global const float4* points, __global const float4* normals,
                                      uint point_count, __global float4* radiance) {
  uint i = get_global_id(0);
  if (i >= point_count) return;
  radiance[i] = (float4)(photon_map_radiance(PHOTON_MAP, points[i].xyz, normals[i].xyz, false), 0.0f);
}
