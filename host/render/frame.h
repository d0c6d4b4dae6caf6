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

// A frame's statistics, one struct per stage. Times are wall seconds less the kernel builds inside them, which count
// in program_s (a cold build on a GPU is seconds: it would swamp the stage); render/timing.h's StageTimer adds them.
// A stage that did not run keeps its zeros.

// The scene as the device holds it. Every frame reports it; the BVH build and upload times only the first frame of a
// Renderer (they are paid once).
struct SceneStats {
  size_t triangles = 0, bvh_nodes = 0, bvh_blocks = 0;
  int bvh_depth = 0;
  double bvh_build_s = 0, upload_s = 0;
  // Materials by how the cache shades their specular lobe (LOBE_*), and whether the BRDF code was compiled at all.
  unsigned lambertian_materials = 0, rough_materials = 0, glossy_materials = 0, hsh_materials = 0;
  bool specular_brdf = false;
  // --light-through-glass caustics in a scene with a glass volume: the glass caustic map (passes/glass_caustics_pass.h),
  // shot once with the scene; its radius in world units.
  bool glass_caustics = false;
  unsigned glass_caustic_paths = 0;
  uint64_t glass_caustic_photons = 0;
  double glass_caustic_radius = 0, glass_caustic_largest_radius = 0, glass_caustic_s = 0;  // radii in world units
};

// Primary visibility, direct light and the image layers gathered on the device (LayerPass), downloaded and filled on
// the host (on a GPU these were half a frame: benchmarks/RESULTS.md, issue 13 on the H200).
struct PrimaryStats {
  unsigned light_samples = 0;  // per pixel, all of its sub-pixels together
  unsigned pixel_samples = 1;  // primary samples per pixel (render/pixel_samples.h)
  uint64_t primary_rays = 0, shadow_rays = 0;
  // Sub-pixels by their lobe: rough (shaded from E), glossy (sampled, kernels/glossy.cl), radiance-cached (LOBE_HSH).
  uint64_t rough_pixels = 0, glossy_pixels = 0, hsh_pixels = 0;
  double gbuffer_s = 0, direct_s = 0, layers_s = 0;
  // Cache methods with area lights or an environment peak (RenderSettings::light_adaptive): the light samples' rounds,
  // their mean per output pixel (sub-pixels with geometry), and the output pixels refined after the first round.
  unsigned light_rounds = 0;
  double light_mean_samples = 0;
  uint64_t light_refined_pixels = 0;
};

// Bounces as rendered (chosen from the scene when --bounces was 0, with the probe's measure) and their method.
struct BounceStats {
  unsigned count = 1;
  BounceMethod method = BounceMethod::path;
  bool chosen = false;
  double kept_per_bounce = 0;
  double probe_s = 0;  // the bounce probe's photons (once per Renderer)
};

// One cache's records as placement made them (render/placement.h): the irradiance records, or the radiance records.
struct RecordStats {
  std::vector<PlacementLevel> levels;
  uint64_t records = 0, rays = 0;
  uint64_t filled_sub_pixels = 0;  // anti-aliasing: sub-pixels no record reached, given the best-weighted one near
  uint64_t at_min_radius = 0, at_max_radius = 0;  // records whose reach sits at a screen-space clamp
  uint64_t adaptive_records = 0;  // records traced again with the full hemisphere (--adaptive-rays)
  double records_s = 0, placement_s = 0, splat_s = 0;
};

// The irradiance cache: its records, then normalisation and composition (resolve), and what no record reached.
struct IrradianceCacheStats : RecordStats {
  uint64_t uncovered_pixels = 0;
  double resolve_s = 0;
};

// Radiance caching of the LOBE_HSH pixels: its records (at a stricter accuracy), the HSH order, the smallest share of
// a cached lobe that order holds, and the lobe table (once per Renderer and seed).
struct RadianceCacheStats : RecordStats {
  unsigned order = 0;
  float accuracy = 0, captured_energy = 0;
  double lobe_table_s = 0;
  double seconds() const { return lobe_table_s + records_s + placement_s + splat_s; }  // the whole stage
};

// The glossy pixels' specular light, sampled per pixel (kernels/glossy.cl).
struct GlossyStats {
  unsigned samples = 0;  // RenderSettings::glossy_samples
  // Adaptive sampling (RenderSettings::glossy_adaptive): the rounds run, the lobe samples per glossy output pixel on
  // average and at most, and the output pixels refined after the first round.
  bool adaptive = false;
  unsigned rounds = 0;
  double mean_samples = 0;
  unsigned most_samples = 0;
  uint64_t refined_pixels = 0;
  uint64_t rays = 0;
  double seconds = 0;
  // Whether the samples read the records where they landed (RenderSettings::glossy_reads_records), and the host's
  // time building the records' grid (within seconds).
  bool reads_records = false;
  double record_grid_s = 0;
};

// The light guide (cache/light_guide.h): its clusters (0: records took no guided rays) and the photons behind them.
struct GuideStats {
  unsigned clusters = 0;
  uint64_t photons = 0;
  double seconds = 0;
};

// The photon map (--bounce-method photons): paths shot, photons kept (landings after a reflection), radius (world
// units); its parts: shooting (device) with the landings kept (host), the grids built (every photon and the surface
// patches sorted on the device, every few photons for lookups on the host), the lookup photons' estimates (device).
struct PhotonMapStats {
  uint64_t paths = 0, photons = 0;
  bool made = false;  // this frame made the map (shot its photons, or read them from a cache file)
  float radius = 0;
  double seconds = 0, shoot_s = 0, grids_s = 0, estimate_s = 0;
};

// The caustic map (cache methods, scenes with a sharp lobe): paths shot, photons kept (landings after a reflection
// off a sharp lobe), radius (world units), and its time (shooting, grid and the pixels' gather).
struct CausticMapStats {
  uint64_t paths = 0, photons = 0;
  float radius = 0;
  double seconds = 0;
};

// Path-traced indirect light.
struct PathStats {
  unsigned samples = 0;
  uint64_t rays = 0;
  double seconds = 0;
};

// Open Image Denoise after the frame (--denoise): the layers it filtered ("direct glossy", "color indirect"), the
// device it ran on, and its time (the library and its device are made before the frame, untimed); of that, the
// time path tracing's indirect layer took, which only `compare`'s indirect row needs (not the image's).
struct DenoiseStats {
  std::string layers, device;
  double seconds = 0, indirect_only_s = 0;
};

// Records kept across frames (render/kept_records.h): what this frame took, added and evicted.
struct KeptRecordsStats {
  uint64_t reused = 0;   // kept records this frame's view took
  uint64_t added = 0;    // placed by this frame
  uint64_t evicted = 0;  // dropped after this frame (the capacity)
  uint64_t moved = 0;    // dropped before this frame because something moved where they see (KeptRecords::drop_moved)
  uint64_t in_place = 0;  // of those, computed again where they stood by this frame (in `added`); the rest went
  uint64_t kept = 0;     // held after this frame
  // Temporal windows (sequence/walkthrough.h): records computed again ahead of the frame, the windows that gave, and
  // the time that took (in the frame's total).
  uint64_t ahead = 0, windows = 0;
  double ahead_s = 0.0;
  uint64_t capacity = 0;
};

struct RenderStats {
  std::string device;
  GiMethod gi = GiMethod::none;
  double program_s = 0, total_s = 0;  // kernel builds (once per device and switch set, then cached on disk); all
  // A frame's time without its kernel builds: what `bench` and `sweep` compare.
  double seconds_without_builds() const { return total_s - program_s; }
  DeviceMemoryUse device_memory;  // this frame's buffers (the scene's included)
  SceneStats scene;
  PrimaryStats primary;
  BounceStats bounces;
  IrradianceCacheStats irradiance;
  RadianceCacheStats radiance;
  GlossyStats glossy;
  GuideStats guide;
  PhotonMapStats photon_map;
  CausticMapStats caustics;
  KeptRecordsStats kept_records;           // irradiance records; all 0 unless the renderer keeps records across frames
  KeptRecordsStats kept_radiance_records;  // radiance records (LOBE_HSH pixels), likewise
  PathStats path;
  DenoiseStats denoise;

  // The stages' times in the order a frame runs them (bench's columns); kernel builds are in none of them.
  struct StageTime {
    const char* name;
    double seconds;
  };
  std::vector<StageTime> stage_times() const {
    return {{"bvh", scene.bvh_build_s},           {"upload", scene.upload_s},
            {"probe", bounces.probe_s},           {"gbuffer", primary.gbuffer_s},
            {"direct", primary.direct_s},         {"photons", photon_map.seconds},
            {"caustics", caustics.seconds},
            {"guide", guide.seconds},             {"records", irradiance.records_s},
            {"placement", irradiance.placement_s}, {"splat", irradiance.splat_s},
            {"radiance", radiance.seconds()},             {"resolve", irradiance.resolve_s},
            {"glossy", glossy.seconds},           {"path", path.seconds},
            {"layers", primary.layers_s}};
  }
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
  // The part of `indirect` sampled per pixel by the glossy pass (sharp lobes: kernels/glossy.cl); empty without one.
  std::vector<float> glossy;
  // With --denoise (render/denoise_frame.h): the layers as rendered, before Open Image Denoise; empty otherwise.
  std::vector<float> noisy_color, noisy_direct, noisy_indirect, noisy_glossy;
  std::vector<CacheRecord> records;      // the cache's records (cache methods)
  RenderStats stats;
};

}  // namespace rcsplat
