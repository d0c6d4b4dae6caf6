// Final gathering from a photon map (--bounce-method photons, ALGORITHM.md section 8): a record's ray that lands on a
// surface takes the light of the bounces after the first from the photons that landed near it, instead of continuing
// its path. Each map photon carries a radiance estimate made once per frame (kernels/photon_map.cl); a lookup returns
// the nearest one's (Christensen 1999, "Faster photon map global illumination").
#ifndef RCSPLAT_PHOTON_MAP_H
#define RCSPLAT_PHOTON_MAP_H
#include "photon_grid.h"
#include "shared_types.h"

// The map as the kernels that read it take it: photons sorted by bucket, their radiance estimates, the buckets' first
// photons (bucket_count + 1 entries) and the grid.
#define PHOTON_MAP_ARGS                                                                                      \
  __global const PhotonHit *map_photons, __global const float4 *map_radiance, __global const uint *map_buckets, \
      PhotonMapParams map
#define PHOTON_MAP map_photons, map_radiance, map_buckets, map

// The estimate of the nearest photon within half a cell of x (the 2 x 2 x 2 cells around x hold every such photon) on a
// surface facing ng's way; none: no light. Reflected radiance, the same in every direction (the map treats every
// surface as Lambertian).
inline float3 photon_map_radiance(PHOTON_MAP_ARGS, float3 x, float3 ng) {
  if (map.photon_count == 0u) return (float3)(0.0f);
  float3 o = vload3(0, map.grid_origin);
  int3 first = convert_int3(floor((x - o) / map.cell_size - 0.5f));
  uint visited[8];
  uint visited_count = 0;
  float nearest = map.radius * map.radius;
  float3 l = (float3)(0.0f);
  for (int c = 0; c < 8; ++c) {
    uint bucket = photon_bucket(first.x + (c & 1), first.y + ((c >> 1) & 1), first.z + (c >> 2), map.bucket_count);
    bool seen = false;
    for (uint v = 0; v < visited_count; ++v) seen = seen || visited[v] == bucket;
    if (seen) continue;
    visited[visited_count++] = bucket;
    for (uint i = map_buckets[bucket]; i < map_buckets[bucket + 1u]; ++i) {
      float3 d = vload3(0, map_photons[i].position) - x;
      float d2 = dot(d, d);
      if (d2 < nearest && dot(vload3(0, map_photons[i].normal), ng) > PHOTON_MIN_NORMAL_COSINE) {
        nearest = d2;
        l = map_radiance[i].xyz;
      }
    }
  }
  return l;
}

#endif
