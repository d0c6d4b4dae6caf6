// The three ways rcsplat computes indirect light for a frame whose G-buffer and direct light are done. Each fills the
// image's indirect layers and the colour, and its part of the statistics.
#pragma once
#include <chrono>

#include "passes/device_scene.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "render/renderer.h"

namespace rcsplat {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct IndirectFrame {
  GpuContext& gpu;
  const Scene& scene;
  const DeviceScene& device_scene;
  GBufferPass& gbuffer;
  DirectPass& direct;
  const RenderSettings& settings;
  RenderedImage& image;  // G-buffer layers, direct light and colour (emission + direct) already filled
};

// The record sampling parameters of these cache settings for records placed at this grid spacing (the spacing clamps
// turned into radius clamps; the fine hemisphere at spacing 1 when one is set).
HemisphereParams hemisphere_params(const CacheSettings& cache, unsigned seed, int spacing);
// Radiance cache splatting on the device: coarse-to-fine placement, records, neighbour clamping, splat, resolve.
void splat_indirect(IndirectFrame& frame);
// The classic irradiance cache (Ward 1988) on the host: Embree rays, an octree lookup, C++ threads.
void octree_indirect(IndirectFrame& frame);
// Placement starts at the largest power of two not above the settings' coarsest spacing.
int coarsest_placement_spacing(const CacheSettings& cache);
// Adds a batch of records placed at this spacing to the per-level counts of the summary.
void count_placed(RenderStats& stats, int spacing, uint32_t records);
// Counts the records whose radius sits at a screen-space clamp, for the summary.
void count_clamped_radii(const std::vector<CacheRecord>& records, const CacheSettings& cache, RenderStats& stats);
// Path-traced indirect light on the device, the ground truth and the competitor.
void path_traced_indirect(IndirectFrame& frame);

}  // namespace rcsplat
