// The two argument prefixes kernels share, so that each is bound by one host helper (DeviceScene::bind and
// GBufferView::bind) and named the same everywhere.
#ifndef RCSPLAT_SCENE_ARGS_H
#define RCSPLAT_SCENE_ARGS_H
#include "shared_types.h"

// With HAS_GLASS_CAUSTICS, the glass caustic map (kernels/glass_caustics.cl, kernels/caustic_map.h): the light that reached a surface through
// a glass volume, which every direct-light estimate reads as the light sources' own.
#if HAS_GLASS_CAUSTICS
#define GLASS_CAUSTIC_ARGS                                                                     \
  , __global const PhotonHit *glass_caustic_photons, __global const uint *glass_caustic_buckets, \
      __global const CausticMapLevel *glass_caustic_levels
#define GLASS_CAUSTIC_MAP glass_caustic_photons, glass_caustic_buckets, glass_caustic_levels
#define GLASS_CAUSTICS_PASSED_ON , GLASS_CAUSTIC_MAP
#else
#define GLASS_CAUSTIC_ARGS
#define GLASS_CAUSTICS_PASSED_ON
#endif

// Everything a ray-tracing kernel may read about the scene: the BVH (nodes as rows of float8, Bvh8Node), per-triangle
// shading data (with normal maps, three tangents a triangle), materials, textures, lights, emissive triangles, the
// environment (kernels/environment.h) and their counts, and the glass caustic map.
#define SCENE_ARGS                                                                                                   \
  __global const float8 *nodes, __global const float8 *blocks, __global const TriangleShading *triangles,           \
      __global const float4 *tangents, __global const Material *materials, __global const TextureInfo *textures,    \
      __global const uint *texels, __global const PunctualLight *lights, __global const EmissiveTriangle *emitters, \
      __global const float4 *environment, __global const float *environment_cdf,                                  \
      SceneCounts scene_counts GLASS_CAUSTIC_ARGS
// Forwards SCENE_ARGS to a function that takes them.
#define SCENE \
  nodes, blocks, triangles, tangents, materials, textures, texels, lights, emitters, environment, environment_cdf,   \
      scene_counts GLASS_CAUSTICS_PASSED_ON

// The G-buffer (what the primary ray through each pixel's centre sees) and its camera, as every pass reads them.
// gbuffer_layers: per pixel, its surface's layers (kernels/brdf_layers.h) in scenes with them (HAS_LAYERS), else one
// unread element.
#define GBUFFER_ARGS                                                          \
  __global const GBufferSample *gbuffer, __global const CameraParams *camera, \
      __global const SurfaceLayers *gbuffer_layers
// Forwards GBUFFER_ARGS to a function that takes them.
#define GBUFFER gbuffer, camera, gbuffer_layers

#endif
