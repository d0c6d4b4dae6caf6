// What a render produces: the image's layers, the cache's records and the statistics of the frame. Plain data (no
// OpenCL), read by the image writers and the command line.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/shared_types.h"
#include "render/settings.h"
#include "util/memory_use.h"

namespace rcsplat {

struct PlacementLevel {
  int spacing_pixels = 0;
  uint32_t records = 0;
};

struct RenderStats {
  std::string device;
  GiMethod gi = GiMethod::none;
  size_t triangles = 0, bvh_nodes = 0, bvh_blocks = 0;
  int bvh_depth = 0;
  unsigned light_samples = 0;  // per pixel, all of its sub-pixels together
  unsigned pixel_samples = 1;  // primary samples per pixel (render/pixel_samples.h)
  double bvh_build_s = 0, upload_s = 0, program_s = 0, gbuffer_s = 0, direct_s = 0, total_s = 0;
  // A frame's time without its kernel builds (once per device and switch set, then cached on disk): what `bench` and
  // `sweep` compare.
  double seconds_without_builds() const { return total_s - program_s; }
  // Work between the passes: the bounce probe's photons, and the image layers gathered on the device (LayerPass),
  // downloaded and filled on the host; on a GPU these were half a frame (benchmarks/RESULTS.md, issue 13 on the H200).
  double probe_s = 0, layers_s = 0;
  DeviceMemoryUse device_memory;  // this frame's buffers (the scene's included)
  uint64_t primary_rays = 0, shadow_rays = 0;
  // Materials by how the cache shades their specular lobe (LOBE_*), and whether the BRDF code was compiled at all.
  unsigned lambertian_materials = 0, rough_materials = 0, glossy_materials = 0, hsh_materials = 0;
  bool specular_brdf = false;
  // Cache methods: glossy pixels' specular light, sampled per pixel (kernels/glossy.cl); rough pixels' from E.
  uint64_t glossy_pixels = 0, rough_pixels = 0, glossy_rays = 0;
  unsigned glossy_samples = 0;
  double glossy_s = 0;
  // Radiance caching (LOBE_HSH pixels): order, the radiance records (placed on those pixels alone, at a stricter
  // accuracy), what the lobe table and the splat cost, and the smallest share of a cached lobe the order holds.
  uint64_t hsh_pixels = 0, radiance_records = 0, radiance_record_rays = 0;
  uint64_t radiance_filled_sub_pixels = 0;  // as filled_sub_pixels, for the radiance records
  unsigned hsh_order = 0;
  float radiance_accuracy = 0, hsh_captured_energy = 0;
  double hsh_table_s = 0, radiance_records_s = 0, radiance_placement_s = 0, radiance_splat_s = 0;
  // Irradiance cache
  std::vector<PlacementLevel> levels;
  uint64_t records = 0, record_rays = 0, uncovered_pixels = 0;
  uint64_t filled_sub_pixels = 0;  // anti-aliasing: sub-pixels no record reached, given the best-weighted one near
  uint64_t records_at_min_radius = 0, records_at_max_radius = 0;  // radius at a screen-space clamp
  uint64_t adaptive_records = 0;  // records traced again with the full hemisphere (--adaptive-rays)
  double records_s = 0, placement_s = 0, splat_s = 0, resolve_s = 0;
  unsigned guide_clusters = 0;  // the light guide's clusters (0: records took no guided rays)
  uint64_t guide_photons = 0;
  double guide_s = 0;
  // Bounces as rendered (chosen from the scene when --bounces was 0, with the scene's measure) and their method.
  unsigned bounces = 1;
  BounceMethod bounce_method = BounceMethod::path;
  bool bounces_chosen = false;
  double kept_per_bounce = 0;
  // The photon map (--bounce-method photons): photons kept (landings after a reflection), radius (world units).
  uint64_t photon_map_paths = 0, photon_map_photons = 0;
  float photon_map_radius = 0;
  double photon_map_s = 0;
  // Its parts: shooting (device) with the landings kept (host), the grids built (host), the lookup photons' estimates
  // uploaded and made (device).
  double photon_map_shoot_s = 0, photon_map_grids_s = 0, photon_map_estimate_s = 0;
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
  std::vector<float> indirect;           // what each pixel's BRDF reflects of the indirect light
  std::vector<float> irradiance;         // E (cache methods)
  std::vector<float> coverage;           // sum of record weights, 0 where uncovered (cache methods)
  std::vector<float> records_per_pixel;  // records that reach each pixel (cache methods)
  std::vector<float> record_positions;   // 1 where a record sits (cache methods)
  std::vector<float> indirect_variance;  // variance of the indirect estimate (path tracing)
  std::vector<CacheRecord> records;      // the cache's records (cache methods)
  RenderStats stats;
};

}  // namespace rcsplat
