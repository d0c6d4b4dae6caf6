// Final gathering from a photon map (--bounce-method photons, ALGORITHM.md section 8): a record's ray that lands on a
// surface takes the light of the bounces after the first from the photons that landed near it, instead of continuing
// its path. Each map photon carries a radiance estimate made once per frame (kernels/photon_map.cl), and a shallow one
// without the map's last landing for a path continued one bounce past a short ray (kernels/bounce.h); a lookup returns
// the nearest one's (Christensen 1999, "Faster photon map global illumination").
#ifndef RCSPLAT_PHOTON_MAP_H
#define RCSPLAT_PHOTON_MAP_H
#include "photon_grid.h"
#include "shared_types.h"

// The map as the kernels that read it take it: photons sorted by bucket, their radiance estimates, the buckets' first
// photons (bucket_count + 1 entries) and the grid.
#define PHOTON_MAP_ARGS                                                                                      \
  __global const PhotonHit *map_photons, __global const float4 *map_radiance, __global const float4 *map_shallow, \
      __global const uint *map_buckets, PhotonMapParams map
#define PHOTON_MAP map_photons, map_radiance, map_shallow, map_buckets, map

// The nearest photon within map.radius of x on a surface facing ng's way (cosine above PHOTON_MIN_NORMAL_COSINE) among
// those in `bucket`: updates *nearest (squared distance) and *l (its estimate, or its shallow one).
inline void nearest_in_bucket(PHOTON_MAP_ARGS, uint bucket, float3 x, float3 ng, bool shallow, float* nearest,
                              float3* l) {
  for (uint i = map_buckets[bucket]; i < map_buckets[bucket + 1u]; ++i) {
    float3 d = vload3(0, map_photons[i].position) - x;
    float d2 = dot(d, d);
    if (d2 < *nearest && dot(vload3(0, map_photons[i].normal), ng) > PHOTON_MIN_NORMAL_COSINE) {
      *nearest = d2;
      *l = shallow ? map_shallow[i].xyz : map_radiance[i].xyz;
    }
  }
}

// The estimate of a photon near x on a surface facing ng's way: the nearest such photon within the radius in x's own
// bucket (its grid cell, one radius wide), or where that holds none, the nearest within half a cell (the 2 x 2 x 2
// cells around x hold every such photon); none: no light. One bucket is what most lookups read: a record's rays
// make millions of them, and each bucket is a cache miss. Reflected radiance, the same in every direction (the map
// treats every surface as Lambertian). shallow: the estimate of the landings before the map's last (map_shallow).
inline float3 photon_map_radiance(PHOTON_MAP_ARGS, float3 x, float3 ng, bool shallow) {
  if (map.photon_count == 0u) return (float3)(0.0f);
  float3 o = vload3(0, map.grid_origin);
  float nearest = map.radius * map.radius;
  float3 l = (float3)(0.0f);
  uint own = photon_bucket(photon_cell(x.x, o.x, map.cell_size), photon_cell(x.y, o.y, map.cell_size),
                           photon_cell(x.z, o.z, map.cell_size), map.bucket_count);
  nearest_in_bucket(PHOTON_MAP, own, x, ng, shallow, &nearest, &l);
  if (nearest < map.radius * map.radius) return l;
  int3 first = convert_int3_sat(floor((x - o) / map.cell_size - 0.5f));
  uint visited[9];
  uint visited_count = 1;
  visited[0] = own;
  for (int c = 0; c < 8; ++c) {
    uint bucket = photon_bucket(first.x + (c & 1), first.y + ((c >> 1) & 1), first.z + (c >> 2), map.bucket_count);
    bool seen = false;
    for (uint v = 0; v < visited_count; ++v) seen = seen || visited[v] == bucket;
    if (seen) continue;
    visited[visited_count++] = bucket;
    nearest_in_bucket(PHOTON_MAP, bucket, x, ng, shallow, &nearest, &l);
  }
  return l;
}

#endif
