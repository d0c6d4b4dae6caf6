// The three ways rcsplat computes indirect light for a frame whose G-buffer and direct light are done. Each fills the
// image's indirect layers and the colour, and its part of the statistics.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "cl/device_scene.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/layer_pass.h"
#include "passes/photon_map_pass.h"
#include "passes/radiance_splat_pass.h"
#include "passes/record_pass.h"
#include "render/frame.h"
#include "render/timing.h"
#include "util/log.h"

namespace rcsplat {

// A step's wall time less the kernel builds inside it, which count in RenderStats::program_s instead (a cold build
// on a GPU is seconds: it would swamp the step).
class TimeWithoutBuilds {
 public:
  explicit TimeWithoutBuilds(const GpuContext& gpu)
      : gpu_(gpu), start_(Clock::now()), builds_before_(gpu.program_seconds()) {}
  double builds() const { return gpu_.program_seconds() - builds_before_; }
  double seconds() const { return seconds_since(start_) - builds(); }

 private:
  const GpuContext& gpu_;
  Clock::time_point start_;
  double builds_before_;
};

struct IndirectFrame {
  GpuContext& gpu;
  const Scene& scene;
  const DeviceScene& device_scene;
  GBufferPass& gbuffer;
  DirectPass& direct;
  const RenderSettings& settings;
  // Output-resolution layers (G-buffer's, direct light, colour = emission + direct) already filled; the passes run on
  // the G-buffer's frame, layers.side() times as wide and high with sub-pixels, and `layers` gathers their images.
  RenderedImage& image;
  LayerPass& layers;
  // The light guide's clusters once attach_light_guide has built them: the irradiance and radiance records and the
  // glossy pass share them.
  std::optional<std::vector<GuideCluster>> light_guide{};
  // The photon map once attach_photon_map has built it: the irradiance and radiance records share it.
  std::unique_ptr<PhotonMapPass> photon_map{};
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
// hands it to the record pass, unless --guide-rays is 0 or the scene has no light with power. Fills its statistics.
void attach_light_guide(IndirectFrame& frame, RecordPass& records);
// The photon map the records read their hits' later bounces from (--bounce-method photons with --bounces 2 or more),
// built on the first call; null otherwise. Fills its statistics.
const PhotonMapPass* attach_photon_map(IndirectFrame& frame);
// Path-traced indirect light on the device, the ground truth and the competitor.
void path_traced_indirect(IndirectFrame& frame);

// Radiance caching of the LOBE_HSH pixels (kernels/hsh_records.cl, kernels/radiance_splat.cl): the pass that holds
// their lobes' indirect light, or nothing when the scene has no radiance-cached material. Fills its statistics.
std::unique_ptr<RadianceSplatPass> radiance_cached_lobes(IndirectFrame& frame);

// The cache methods' last step: glossy pixels' specular light sampled from their lobes (GlossyPass, when the scene has
// a glossy material; also the LOBE_HSH pixels when radiance_cached is null), then composition (ComposePass) of the
// cached irradiance (float4 per pixel: E, weight) and the radiance-cached lobes into the image's indirect and colour
// layers.
void compose_cached_indirect(IndirectFrame& frame, const cl::Buffer& irradiance,
                             const RadianceSplatPass* radiance_cached = nullptr);
// The cache methods' own layers at output resolution: irradiance, coverage, records reaching and sitting in each
// pixel, and the uncovered sub-pixels counted. irradiance: float4 (E.rgb, weight, 0 where uncovered);
// records_per_pixel: uint; record_at_pixel: int, -1 where no record sits.
void fill_cache_layers(IndirectFrame& frame, const cl::Buffer& irradiance, const cl::Buffer& records_per_pixel,
                       const cl::Buffer& record_at_pixel);

}  // namespace rcsplat
