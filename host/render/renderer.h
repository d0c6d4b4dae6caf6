// The render pipeline, pass after pass: BVH build and upload, primary visibility, direct light, composition.
#pragma once
#include <string>
#include <vector>

#include "cl/gpu_context.h"
#include "render/camera.h"
#include "scene/scene.h"

namespace rcsplat {

struct RenderSettings {
  int width = 0, height = 0;  // 0: derived (see resolve_resolution)
  int camera = 0;
  CameraOverrides camera_overrides;
  unsigned light_samples = 16;  // per pixel on emissive triangles; rounded up to a square number of strata
  unsigned seed = 0;
};

struct RenderStats {
  std::string device;
  size_t triangles = 0, bvh_nodes = 0, bvh_blocks = 0;
  int bvh_depth = 0;
  unsigned light_samples = 0;
  double bvh_build_s = 0, upload_s = 0, program_s = 0, gbuffer_s = 0, direct_s = 0, total_s = 0;
  uint64_t primary_rays = 0, shadow_rays = 0;
};

// Linear images, row-major from the top, three floats a pixel (depth: one).
struct RenderedImage {
  int width = 0, height = 0;
  std::vector<float> color;     // emission + direct
  std::vector<float> direct;    // reflected direct light
  std::vector<float> emission;  // light emitted toward the camera
  std::vector<float> albedo;
  std::vector<float> normal;    // shading normal, world space
  std::vector<float> position;  // world-space position of the primary hit
  std::vector<float> depth;     // distance along the primary ray; 0 where nothing was hit
  std::vector<int> triangle;    // the primary hit's triangle, -1 where nothing was hit
  RenderStats stats;
};

RenderedImage render_direct(GpuContext& gpu, const Scene& scene, const RenderSettings& settings);

}  // namespace rcsplat
