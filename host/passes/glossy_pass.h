// The specular indirect light of glossy pixels (kernels/glossy.cl), sampled from each pixel's own lobe; the cache
// carries the rest. Compiled and run only for scenes with a glossy material (DeviceScene's HAS_SPECULAR_BRDF).
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "util/test_probe.h"
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "cache/world_record_grid.h"
#include "kernels/shared_types.h"
#include "passes/caustic_map_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/path_queue.h"
#include "passes/ray_queue.h"
#include "passes/world_record_grid_pass.h"

namespace rcsplat {

// What the samples' rays read where they land on a Lambertian or rough surface (kernels/glossy.cl sample_radiance):
// the cache's records by position, with their grid, built on the device where the records are (frames: `device`), or
// on the host and uploaded (tests: `records` and `grid`). With a caustic map, the records' irradiance holds the map's
// at each record too (CausticMapPass::lit_records), and a path past a hit that no record reaches reads the map there
// (kernels/glossy.cl glossy_path_step). No records: every sample continues its path.
struct GlossyCacheReads {
  const std::vector<CacheRecord>* records = nullptr;
  const WorldRecordGrid* grid = nullptr;
  const DeviceWorldRecordGrid* device = nullptr;
  const CausticMapPass* caustics = nullptr;
};

// The frame's other light at each sub-pixel, which the first round's error estimate divides by (a pixel's error is
// relative to all its light): DirectPass's radiance and the cache's irradiance (float4 per sub-pixel). Without them
// (tests) the glossy light alone.
struct GlossyFrameLight {
  const cl::Buffer* direct = nullptr;
  const cl::Buffer* irradiance = nullptr;
};

// How a run spent its samples.
struct GlossyRunStats {
  unsigned rounds = 0;
  uint64_t chunks = 0;             // chunks taken by sub-pixels that sample a lobe, every round
  uint64_t sampled_sub_pixels = 0; // those sub-pixels
  uint64_t refined_pixels = 0;     // output pixels that took a round after the first
  unsigned most_chunks = 0;        // the most one sub-pixel took
};

class GlossyPass {
 public:
  // sample_radiance_cacheable: also sample the LOBE_HSH pixels (cache methods without radiance caching: the octree).
  GlossyPass(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable);
  // samples: lobe samples per output pixel that samples a lobe, on average over the frame (the budget), split among
  // its sub-pixels (GBufferView::sub_pixel_side). With `adaptive`, each sampled sub-pixel takes one chunk
  // (GLOSSY_CHUNK_LOBE lobe samples and, where its lobe faces a cone of the light guide, GLOSSY_CHUNK_GUIDED aimed at
  // it), then the output pixels whose estimated error gains most take more in later rounds (passes/sample_rounds.h),
  // their strata nested so that every count stays stratified; without it, every sampled sub-pixel takes the budget's
  // chunks in one round. With radiance records that left the guide's share to the pixels (record_guide_rays guided
  // rays beside record_strata strata, both > 0), the radiance-cached sub-pixels get that share from samples /
  // sub-pixels samples each. Blocks until done.
  GlossyRunStats run(const GBufferView& gbuffer, unsigned samples, unsigned seed,
                     const std::vector<GuideCluster>& guide = {}, unsigned record_strata = 0,
                     unsigned record_guide_rays = 0, unsigned bounces = 1, const GlossyCacheReads& reads = {},
                     const GlossyFrameLight& frame_light = {}, bool adaptive = true);
  const cl::Buffer& radiance() const { return radiance_; }  // float4 per pixel: RGB, A = rays cast

 private:
  friend struct test::PassProbe;  // what a sample reads of the records (tests/pass_probe.h)
  static constexpr const char* kProgram = "glossy.cl";  // its kernels' file
  // The records the samples read and their grid: the device's, or uploaded from the host (an empty grid without
  // them); bind_records then sets a kernel's WORLD_RECORD_ARGS to them, and bind_cached_light those and its
  // CAUSTIC_MAP_ARGS to the caustic map (an empty one, which the kernels never read, without it).
  void prepare_records(const GlossyCacheReads& reads);
  void bind_records(NamedKernel& kernel);
  void bind_cached_light(NamedKernel& kernel);
  // One round over item_count output pixels (listed in pixel_list_ when params.listed): each sub-pixel's samples
  // whole (kernel_) or as the wavefront (GroupSizes::record_trace): the sub-pixels in launches, each sample's ray
  // traced, its first hit shaded, the paths going on queued and stepped a kernel a bounce, then each sub-pixel's
  // samples summed (kernels/glossy.cl).
  void run_round(const GBufferView& gbuffer, const GlossyParams& params, size_t item_count);
  void run_wavefront(const GBufferView& gbuffer, const GlossyParams& params, size_t item_count);
  // After the first round: which output pixels take more (sample_rounds.h), for chunks_per_sampled_sub_pixel on
  // average in all.
  std::vector<uint8_t> refinement_levels(const GBufferView& gbuffer, const GlossyFrameLight& frame_light,
                                         double chunks_per_sampled_sub_pixel, GlossyRunStats& stats);

  GpuContext& gpu_;
  const DeviceScene& scene_;
  KernelDefines defines_;
  NamedKernel kernel_, aim_, trace_, shade_first_hits_, step_paths_, finish_paths_, gather_, pixel_error_, average_;
  cl::Buffer radiance_, guide_;
  // Per sub-pixel: its chunks' summed estimates (RGB) and rays (A); its samples' luminance sum, sum of squares, count
  // and its chunks. Per output pixel: the first round's error estimate; a later round's list of pixels.
  cl::Buffer sums_, moments_, pixel_errors_, pixel_list_, no_frame_light_;
  cl::Buffer records_, record_starts_, record_lists_;  // uploaded each frame that reads records from the host
  const cl::Buffer *bound_records_ = nullptr, *bound_starts_ = nullptr, *bound_lists_ = nullptr;
  WorldRecordParams bound_grid_{};
  const CausticMapPass* bound_caustics_ = nullptr;
  cl::Buffer no_caustic_photons_, no_caustic_buckets_;  // the empty map's placeholders
  // The wavefront's per-launch buffers: each sample's slot (its direction, then its light), hit, and the queue of
  // paths going on after their first hit.
  cl::Buffer sample_slots_, sample_hits_;
  PathQueue paths_;
  std::optional<RayQueue> rays_;  // made for the first wavefront launch (its program built only then)
  size_t pixels_ = 0, errors_capacity_ = 0, list_capacity_ = 0, guide_capacity_ = 0, records_capacity_ = 0, starts_capacity_ = 0, lists_capacity_ = 0,
         slots_capacity_ = 0, hits_capacity_ = 0;
};

}  // namespace rcsplat
