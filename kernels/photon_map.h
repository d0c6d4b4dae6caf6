// Final gathering from a photon map (--bounce-method photons, docs/ALGORITHM.md section 8): a record's ray that lands on a
// surface takes the light of the bounces after the first from the photons that landed near it, instead of continuing
// its path. Each lookup photon carries two estimates made once per frame (kernels/photon_map.cl): the light its
// neighbours' surfaces reflect (their albedo averaged in) and the irradiance, both over pi; a lookup reflects them by
// its own surface's lobe toward its ray (kernels/bounce.h photon_gather). A shallow pair leaves out the map's last
// landing, for a path continued one bounce past a short ray. A lookup takes the nearest photon's (Christensen 1999,
// "Faster photon map global illumination").
#ifndef RCSPLAT_PHOTON_MAP_H
#define RCSPLAT_PHOTON_MAP_H
#include "photon_grid.h"
#include "shared_types.h"

// The map as the kernels that read it take it: photons sorted by bucket, their estimates (two float4 per photon: the
// reflected light, the irradiance), the buckets' first photons
// (bucket_count + 1 entries) and the grid.
#define PHOTON_MAP_ARGS                                                                                      \
  __global const PhotonHit *map_photons, __global const float4 *map_radiance, __global const float4 *map_shallow, \
      __global const uint *map_buckets, PhotonMapParams map
#define PHOTON_MAP map_photons, map_radiance, map_shallow, map_buckets, map

// Whether `bucket` is not among the first *count of visited (cells of a hashed grid can share a bucket), and if so
// adds it: each bucket is searched once.
inline bool first_visit(uint bucket, uint* visited, uint* count) {
  for (uint v = 0; v < *count; ++v)
    if (visited[v] == bucket) return false;
  visited[(*count)++] = bucket;
  return true;
}

// Whether a point at offset d from a disc's centre (normal n) on a surface facing m lies in the disc: within the
// radius, within PHOTON_DISC_HALF_THICKNESS r of the tangent plane, and facing within PHOTON_MIN_NORMAL_COSINE.
inline bool in_disc(float3 d, float3 m, float3 n, float r2, float half_thickness) {
  return dot(d, d) < r2 && fabs(dot(d, n)) < half_thickness && dot(m, n) > PHOTON_MIN_NORMAL_COSINE;
}

// The nearest photon within map.radius of x on a surface facing ng's way (cosine above PHOTON_MIN_NORMAL_COSINE) among
// those in `bucket`: updates *nearest (squared distance) and *index.
inline void nearest_in_bucket(PHOTON_MAP_ARGS, uint bucket, float3 x, float3 ng, float* nearest, int* index) {
  for (uint i = map_buckets[bucket]; i < map_buckets[bucket + 1u]; ++i) {
    float3 d = vload3(0, map_photons[i].position) - x;
    float d2 = dot(d, d);
    if (d2 < *nearest && dot(vload3(0, map_photons[i].normal), ng) > PHOTON_MIN_NORMAL_COSINE) {
      *nearest = d2;
      *index = (int)i;
    }
  }
}

// The lookup photon whose estimates stand for x on a surface facing ng's way: the nearest such photon within the
// radius in x's own bucket (its grid cell, one radius wide), or where that holds none, the nearest within half a cell
// (the 2 x 2 x 2 cells around x hold every such photon); -1: none, no light. One bucket is what most lookups read: a
// record's rays make millions of them, and each bucket is a cache miss.
inline int photon_map_nearest(PHOTON_MAP_ARGS, float3 x, float3 ng) {
  if (map.photon_count == 0u) return -1;
  float3 o = vload3(0, map.grid_origin);
  float nearest = map.radius * map.radius;
  int index = -1;
  uint own = photon_bucket(photon_cell(x.x, o.x, map.cell_size), photon_cell(x.y, o.y, map.cell_size),
                           photon_cell(x.z, o.z, map.cell_size), map.bucket_count);
  nearest_in_bucket(PHOTON_MAP, own, x, ng, &nearest, &index);
  if (index >= 0) return index;
  int3 first = convert_int3_sat(floor((x - o) / map.cell_size - 0.5f));
  uint visited[9];
  uint visited_count = 1;
  visited[0] = own;
  for (int c = 0; c < 8; ++c) {
    uint bucket = photon_bucket(first.x + (c & 1), first.y + ((c >> 1) & 1), first.z + (c >> 2), map.bucket_count);
    if (!first_visit(bucket, visited, &visited_count)) continue;
    nearest_in_bucket(PHOTON_MAP, bucket, x, ng, &nearest, &index);
  }
  return index;
}

#endif
