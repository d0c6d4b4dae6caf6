// The three ways rcsplat computes indirect light for a frame whose G-buffer and direct light are done. Each fills the
// image's indirect layers and the colour, and its part of the statistics.
#pragma once
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "cl/device_scene.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/layer_pass.h"
#include "passes/brdf_table_pass.h"
#include "passes/caustic_map_pass.h"
#include "passes/compose_pass.h"
#include "passes/glossy_pass.h"
#include "passes/hsh_record_pass.h"
#include "passes/path_pass.h"
#include "passes/photon_map_pass.h"
#include "passes/radiance_splat_pass.h"
#include "passes/record_pass.h"
#include "passes/splat_pass.h"
#include "passes/world_record_grid_pass.h"
#include "render/device_record_index.h"
#include "render/frame.h"
#include "render/frame_plan.h"
#include "render/kept_records.h"
#include "render/timing.h"
#include "util/log.h"

namespace rcsplat {

// The lobe table of the radiance-cached (LOBE_HSH) materials at the highest order (kernels/brdf_table.cl), computed
// once per scene and seed: the plan chooses the HSH order and the radiance records' accuracy from it.
struct RadianceLobeTable {
  BrdfTable full;
  size_t materials = 0;                // rows of `full`: the LOBE_HSH materials
  std::vector<int> row_of_material;    // each material's row, -1 where it is not radiance-cached
  float sharpest_roughness = 1.0f;
};
RadianceLobeTable radiance_lobe_table(GpuContext& gpu, const DeviceScene& device_scene, unsigned seed);
// The smallest order that holds 95% of what the highest holds of every cached lobe.
unsigned automatic_hsh_order(const RadianceLobeTable& table);
// The smallest share of a cached lobe that `order` holds.
float hsh_captured_energy(const RadianceLobeTable& table, unsigned order);
// Radiance caching's stricter accuracy for glossier lobes: a times the sharpest cached roughness (the lobe's angular
// width goes as roughness^2 = alpha; roughness itself keeps records from crowding), at least a / 2.
float radiance_accuracy(const RadianceLobeTable& table, float accuracy);

// What the records read that does not depend on the view, each with the settings it was built for: the Renderer
// keeps them across frames and rebuilds one only when its settings change (same settings, same bits).
struct ViewIndependentLight {
  // The light guide's clusters (attach_light_guide): the irradiance and radiance records and the glossy pass share
  // them. Depends on the seed and --guide-rays' photons.
  struct Guide {
    unsigned seed = 0, photons = 0;
    std::vector<GuideCluster> clusters;
    uint64_t hits = 0;
  };
  std::optional<Guide> guide;
  // The photon map (attach_photon_map): the irradiance and radiance records share it.
  struct PhotonKey {
    unsigned seed = 0, bounces = 0, paths = 0, neighbours = 0;
    bool operator==(const PhotonKey&) const = default;
  };
  std::optional<PhotonKey> photon_key;
  std::unique_ptr<PhotonMapPass> photon_map;
  uint64_t photon_paths = 0, photons = 0;
  float photon_radius = 0.0f;  // world units
  // The caustic map (attach_caustic_map): depends on the seed, --caustic-photons and --photon-neighbours.
  struct CausticKey {
    unsigned seed = 0, paths = 0, neighbours = 0;
    bool operator==(const CausticKey&) const = default;
  };
  std::optional<CausticKey> caustic_key;
  std::unique_ptr<CausticMapPass> caustic_map;
  uint64_t caustic_photons = 0;
  float caustic_radius = 0.0f;  // world units
};

// A pass the Renderer keeps across frames while what it was compiled or sized for (its key) stays the same, and makes
// again when that changes. Each frame begins it (begin_frame or begin), which resets what a frame accumulates.
template <typename Pass, typename Key = std::monostate>
class KeptPass {
 public:
  template <typename Make>
  Pass& get(const Key& key, Make&& make) {
    if (!pass_ || !(key_ == key)) {
      pass_.reset();  // the old pass's buffers go before the new one's are made
      pass_ = make();
      key_ = key;
    }
    return *pass_;
  }

 private:
  std::unique_ptr<Pass> pass_;
  Key key_{};
};

// The per-method passes with their buffers, kept by the Renderer so that a later frame of the same method makes no
// program, kernel or buffer again (tests/gi_test.cpp, Renderer tests). Only one method's passes are held at a time.
struct MethodPasses {
  // A record pass's program: hemisphere rows, and whether its rays read a photon map.
  struct RecordKey {
    unsigned theta_strata = 0;
    bool photon_gather = false;
    bool caustics_apart = false;  // its rays leave light -> glossy -> record to the caustic map
    bool operator==(const RecordKey&) const = default;
  };
  // The lobe table a radiance splat holds: its order and the seed the table was sampled with.
  struct LobeKey {
    unsigned order = 0, seed = 0;
    bool operator==(const LobeKey&) const = default;
  };
  GiMethod method = GiMethod::none;
  KeptPass<RecordPass, RecordKey> irradiance_records, radiance_records;
  KeptPass<DeviceRecordIndex> irradiance_index, radiance_index;
  KeptPass<SplatPass> splat;
  KeptPass<GlossyPass, bool> glossy;    // whether it samples the LOBE_HSH pixels too
  KeptPass<WorldRecordGridPass> world_record_grid;  // the records the glossy pass reads, by position
  KeptPass<ComposePass, bool> compose;  // whether the LOBE_HSH pixels' lobes come from radiance records
  KeptPass<RadianceSplatPass, LobeKey> radiance_splat;
  KeptPass<HshRecordPass, unsigned> hsh_records;  // the order
  KeptPass<PathPass> path;
  // The kept records the last frame computed again in place (render/indirect_splat.cpp), for a look ahead
  // (Renderer::look_ahead): the pass that computed them, the pixels and the slots, the hemisphere.
  struct InPlaceBatch {
    RecordPass* pass = nullptr;
    std::vector<cl_uint> pixels;
    uint32_t first = 0;
    HemisphereParams hemisphere{};
  } in_place;
};

struct IndirectFrame {
  GpuContext& gpu;
  const Scene& scene;
  const DeviceScene& device_scene;
  GBufferPass& gbuffer;
  DirectPass& direct;
  // The frame's plan, passes included (render/frame_passes.h): what runs is read there, never decided again.
  const FramePlan& plan;
  // plan.frame_settings() for this frame, or a round's share of it (path tracing over the pixel's area:
  // Renderer::path_trace_pixel_area).
  const RenderSettings& settings;
  // Output-resolution layers (G-buffer's, direct light, colour = emission + direct) already filled; the passes run on
  // the G-buffer's frame, layers.side() times as wide and high with sub-pixels, and `layers` gathers their images.
  RenderedImage& image;
  LayerPass& layers;
  // The light guide and the photon map: built by the first frame that needs them, kept by the Renderer.
  ViewIndependentLight& light;
  // The method's passes, kept by the Renderer.
  MethodPasses& passes;
  // The lobe table of the radiance-cached materials (null: the scene has none), kept by the Renderer and sampled with
  // plan.settings.seed; the plan derived its order and accuracy from it (FramePlan::radiance_accuracy).
  const RadianceLobeTable* lobe_table = nullptr;
  // The frame's camera (the G-buffer's, in device coordinates) and the irradiance and radiance records kept across
  // frames (null: a cache of this frame's own; render/kept_records.h).
  const CameraParams* camera = nullptr;
  KeptRecords* kept_records = nullptr;
  KeptRecords* kept_radiance_records = nullptr;
  // The photons and clusters the light was made from, kept with the records for cache files (null with a cache of the
  // frame's own). A Renderer that has no map yet builds it from the photons here when there are some (a cache file's).
  KeptLight* kept_light = nullptr;
  // The path tracer's progress when several rounds share it (null: its own), and its samples before this frame's.
  Progress* progress = nullptr;
  size_t progress_done_before = 0;
};

// Radiance cache splatting on the device: coarse-to-fine placement, records, neighbour clamping, splat, resolve.
void splat_indirect(IndirectFrame& frame);
// The classic irradiance cache (Ward 1988): the same placement and records, but coverage, clamping and the final
// interpolation through an octree on the host.
void octree_indirect(IndirectFrame& frame);
// Builds the frame's light guide (photons from the lights, clustered: cache/light_guide.h) on its first call, and
// hands it to the record pass, when the plan's passes have one (FramePasses::light_guide). Fills its statistics.
void attach_light_guide(IndirectFrame& frame, RecordPass& records);
// The light guide built for this frame's settings, or null (none asked for, or not built yet).
const std::vector<GuideCluster>* frame_light_guide(const IndirectFrame& frame);
// The photon map the records read their hits' later bounces from (FramePasses::photon_map), built on the first call;
// null when the plan has none. Fills its statistics.
const PhotonMapPass* attach_photon_map(IndirectFrame& frame);
// The caustic map the pixels read (FramePasses::caustic_map), built on the first call; null when the plan has none.
// Fills its statistics.
CausticMapPass* attach_caustic_map(IndirectFrame& frame);
// The scene's surface area in device units: the photon maps' radii start from their photons spread over it.
double device_surface_area(const Scene& scene, const SceneFrame& frame);
// The frame's record pass, for irradiance records or (radiance) radiance records that keep their strata, kept in
// frame.passes and begun for this frame: its photon map (attach_photon_map), bounces and light guide
// (attach_light_guide). Its kernel builds count in the statistics' program_s.
RecordPass& frame_record_pass(IndirectFrame& frame, const CacheSettings& cache, bool radiance);
// Path-traced indirect light on the device, the ground truth and the competitor.
void path_traced_indirect(IndirectFrame& frame);

// Radiance caching of the LOBE_HSH pixels (kernels/hsh_records.cl, kernels/radiance_splat.cl): the pass (kept in
// frame.passes) that holds their lobes' indirect light, or null when the plan has no radiance records
// (FramePasses::radiance_records). Fills its statistics.
const RadianceSplatPass* radiance_cached_lobes(IndirectFrame& frame);

// The cache methods' last step: glossy pixels' specular light sampled from their lobes (GlossyPass, when the plan has
// it: FramePasses::glossy), then composition (ComposePass) of the
// cached irradiance (float4 per pixel: E, weight) and the radiance-cached lobes into the image's indirect and colour
// layers. records: the record_count irradiance records the cached irradiance came from, on the device; with
// RenderSettings::glossy_reads_records the glossy samples read them where they land (kernels/glossy.cl
// sample_radiance; null: they continue paths).
void compose_cached_indirect(IndirectFrame& frame, const cl::Buffer& irradiance,
                             const RadianceSplatPass* radiance_cached, const cl::Buffer* records,
                             uint32_t record_count);
// The cache methods' own layers at output resolution: irradiance, coverage, records reaching and sitting in each
// pixel, and the uncovered sub-pixels counted. irradiance: float4 (E.rgb, weight, 0 where uncovered);
// records_per_pixel: uint; record_at_pixel: int, -1 where no record sits.
void fill_cache_layers(IndirectFrame& frame, const cl::Buffer& irradiance, const cl::Buffer& records_per_pixel,
                       const cl::Buffer& record_at_pixel);

}  // namespace rcsplat
