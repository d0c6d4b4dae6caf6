// The caustic map (Jensen 1996): photons from the lights that reflected once off a sharp lobe (LOBE_GLOSSY) before
// landing (kernels/light_guide.cl with PhotonParams::caustic), read at the pixels as irradiance. Records leave that
// path out of their rays (kernels/bounce.h hit_direct_without_caustics), so each of light -> glossy -> surface ->
// camera is counted once: here. The estimate is a plain density, the incident flux of the photons in a disc of the
// map's radius about the point over the disc's area, on surfaces facing the point's way (in_disc); the radius is made
// small where the photons crowd (host/passes/caustic_map_pass.h), since a caustic is as sharp as the highlight that
// casts it.
#include "caustic_map.h"
#include "scene_args.h"

// Adds each G-buffer sample's caustic irradiance to the cached irradiance composition reads (kernels/compose.cl),
// which reflects it by the sample's BRDF as it does the records' light: every lobe's diffuse base, a rough lobe's
// albedo too. Radiance-cached lobes take theirs from their own records, which keep the caustic paths.
__kernel void add_caustics(GBUFFER_ARGS, CAUSTIC_MAP_ARGS, __global float4* irradiance) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[i];
  if (g.triangle < 0) return;
  float3 e = caustic_irradiance(CAUSTIC_MAP, vload3(0, g.position), vload3(0, g.geometric_normal));
  irradiance[i] += (float4)(e, 0.0f);
}

// caustic_irradiance at query points (xyz) on surfaces facing these normals, for tests.
__kernel void caustic_irradiance_at(CAUSTIC_MAP_ARGS, __global const float4* points, __global const float4* normals,
                                    uint point_count, __global float4* irradiance) {
  uint i = get_global_id(0);
  if (i >= point_count) return;
  irradiance[i] = (float4)(caustic_irradiance(CAUSTIC_MAP, points[i].xyz, normals[i].xyz), 0.0f);
}

// Each record with the caustic irradiance at its point added to its own: the records a glossy sample reads then stand
// for all the light there (kernels/glossy.cl), which costs one lookup per record, not one per sample.
__kernel void add_caustics_to_records(CAUSTIC_MAP_ARGS, __global const CacheRecord* records, uint record_count,
                                      __global CacheRecord* lit) {
  uint i = get_global_id(0);
  if (i >= record_count) return;
  CacheRecord r = records[i];
  float3 e = caustic_irradiance(CAUSTIC_MAP, vload3(0, r.position), vload3(0, r.normal));
  r.irradiance[0] += e.x;
  r.irradiance[1] += e.y;
  r.irradiance[2] += e.z;
  lit[i] = r;
}
