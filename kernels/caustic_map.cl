// The caustic map (Jensen 1996): photons from the lights that reflected once off a sharp lobe (LOBE_GLOSSY) before
// landing (kernels/light_guide.cl with PhotonParams::caustic), read at the pixels as irradiance. Records leave that
// path out of their rays (kernels/bounce.h hit_direct_without_caustics), so each of light -> glossy -> surface ->
// camera is counted once: here. The estimate is a plain density, the incident flux of the photons in a disc of the
// map's radius about the point over the disc's area, on surfaces facing the point's way (in_disc); the radius is made
// small where the photons crowd (host/passes/caustic_map_pass.h), since a caustic is as sharp as the highlight that
// casts it.
#include "photon_map.h"
#include "sampling.h"
#include "scene_args.h"

// The caustic irradiance at x on a surface facing ng's way: the photons of the 3 x 3 x 3 cells about x (cells are at
// least a radius wide) that lie in the disc of radius grid.radius about x, their incident flux over pi r^2.
inline float3 caustic_irradiance(__global const PhotonHit* photons, __global const uint* buckets, PhotonMapParams grid,
                                 float3 x, float3 ng) {
  if (grid.photon_count == 0u) return (float3)(0.0f);
  float r2 = grid.radius * grid.radius, half_thickness = PHOTON_DISC_HALF_THICKNESS * grid.radius;
  float3 o = vload3(0, grid.grid_origin), sum = (float3)(0.0f);
  int cx = photon_cell(x.x, o.x, grid.cell_size), cy = photon_cell(x.y, o.y, grid.cell_size),
      cz = photon_cell(x.z, o.z, grid.cell_size);
  uint visited[27];
  uint visited_count = 0;
  for (int c = 0; c < 27; ++c) {
    uint bucket = photon_bucket(cx + c % 3 - 1, cy + (c / 3) % 3 - 1, cz + c / 9 - 1, grid.bucket_count);
    if (!first_visit(bucket, visited, &visited_count)) continue;
    for (uint j = buckets[bucket]; j < buckets[bucket + 1u]; ++j)
      if (in_disc(vload3(0, photons[j].position) - x, vload3(0, photons[j].normal), ng, r2, half_thickness))
        sum += vload3(0, photons[j].incident);
  }
  return finite_or_zero(sum / (RC_PI * r2));
}

// Adds each G-buffer sample's caustic irradiance to the cached irradiance composition reads (kernels/compose.cl),
// which reflects it by the sample's BRDF as it does the records' light: every lobe's diffuse base, a rough lobe's
// albedo too. Radiance-cached lobes take theirs from their own records, which keep the caustic paths.
__kernel void add_caustics(GBUFFER_ARGS, __global const PhotonHit* photons, __global const uint* buckets,
                           PhotonMapParams grid, __global float4* irradiance) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[i];
  if (g.triangle < 0) return;
  float3 e = caustic_irradiance(photons, buckets, grid, vload3(0, g.position), vload3(0, g.geometric_normal));
  irradiance[i] += (float4)(e, 0.0f);
}

// caustic_irradiance at query points (xyz) on surfaces facing these normals, for tests.
__kernel void caustic_irradiance_at(__global const PhotonHit* photons, __global const uint* buckets,
                                    PhotonMapParams grid, __global const float4* points,
                                    __global const float4* normals, uint point_count, __global float4* irradiance) {
  uint i = get_global_id(0);
  if (i >= point_count) return;
  irradiance[i] = (float4)(caustic_irradiance(photons, buckets, grid, points[i].xyz, normals[i].xyz), 0.0f);
}
