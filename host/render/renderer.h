// The render pipeline, pass after pass: BVH build and upload, primary visibility, direct light, then indirect light by
// radiance cache splatting (or the classic octree lookup, or path tracing), and composition.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "render/camera.h"
#include "scene/scene.h"

namespace rcsplat {

enum class GiMethod { none, splat, octree, path };
const char* gi_method_name(GiMethod method);

// The irradiance cache's controls (ALGORITHM.md sections 3 to 7).
struct CacheSettings {
  float accuracy = 0.3f;        // a: smaller means more records and less error
  unsigned theta_strata = 16;   // hemisphere rays per record: M x N
  unsigned phi_strata = 32;
  // Rays for the records placed at the finest level (spacing 1), which reach only a few pixels each; 0: M x N too.
  unsigned fine_theta_strata = 0, fine_phi_strata = 0;
  // Record spacing: a record's reach a * R is clamped to [min, max] pixel footprints at the record (as pbrt-v2 clamps
  // its contribution extent), so R itself to [min, max] / a. Keeps records from crowding corners and from vanishing
  // on open areas.
  float min_spacing = 3.0f;
  float max_spacing = 20.0f;
  int coarsest_spacing = 32;    // record placement starts on this pixel grid and halves it down to 1
};

struct PathSettings {
  unsigned samples = 64;  // per pixel
  bool stratified = false;
};

struct RenderSettings {
  int width = 0, height = 0;  // 0: derived (see resolve_resolution)
  int camera = 0;
  CameraOverrides camera_overrides;
  unsigned light_samples = 16;  // per pixel on emissive triangles; rounded up to a square number of strata
  unsigned seed = 0;
  GiMethod gi = GiMethod::splat;
  CacheSettings cache;
  PathSettings path;
};

struct PlacementLevel {
  int spacing = 0;
  uint32_t records = 0;
};

struct RenderStats {
  std::string device;
  GiMethod gi = GiMethod::none;
  size_t triangles = 0, bvh_nodes = 0, bvh_blocks = 0;
  int bvh_depth = 0;
  unsigned light_samples = 0;
  double bvh_build_s = 0, upload_s = 0, program_s = 0, gbuffer_s = 0, direct_s = 0, total_s = 0;
  uint64_t primary_rays = 0, shadow_rays = 0;
  // Irradiance cache
  std::vector<PlacementLevel> levels;
  uint64_t records = 0, record_rays = 0, uncovered_pixels = 0;
  uint64_t records_at_min_radius = 0, records_at_max_radius = 0;  // radius at a screen-space clamp
  double records_s = 0, placement_s = 0, splat_s = 0, resolve_s = 0;
  // Path tracing
  unsigned path_samples = 0;
  uint64_t path_rays = 0;
  double path_s = 0;
};

// Linear images, row-major from the top, three floats a pixel (one-channel layers: one).
struct RenderedImage {
  int width = 0, height = 0;
  std::vector<float> color;     // emission + direct + indirect
  std::vector<float> direct;    // reflected direct light
  std::vector<float> emission;  // light emitted toward the camera
  std::vector<float> albedo;
  std::vector<float> normal;    // shading normal, world space
  std::vector<float> position;  // world-space position of the primary hit
  std::vector<float> depth;     // distance along the primary ray; 0 where nothing was hit
  std::vector<int> triangle;    // the primary hit's triangle, -1 where nothing was hit
  // Indirect light; empty when not computed.
  std::vector<float> indirect;           // albedo / pi * E
  std::vector<float> irradiance;         // E (cache methods)
  std::vector<float> coverage;           // sum of record weights, 0 where uncovered (cache methods)
  std::vector<float> records_per_pixel;  // records that reach each pixel (cache methods)
  std::vector<float> record_positions;   // 1 where a record sits (cache methods)
  std::vector<float> indirect_variance;  // variance of the indirect estimate (path tracing)
  std::vector<CacheRecord> records;      // the cache's records (cache methods)
  RenderStats stats;
};

// Validates the cache settings; throws rcsplat::Error naming the bad one.
void check_cache_settings(const CacheSettings& cache);

RenderedImage render(GpuContext& gpu, const Scene& scene, const RenderSettings& settings);

}  // namespace rcsplat
