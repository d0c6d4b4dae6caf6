// Record computation (kernels/records.cl): owns the record array, which grows as placement adds batches, and the
// per-ray samples a launch traces before they are reduced into records. Both cache methods compute their records here,
// so they are the same records.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/gbuffer_pass.h"
#include "passes/path_queue.h"
#include "passes/ray_queue.h"
#include "passes/photon_map_pass.h"

namespace rcsplat {

// What adaptive rays compare with their threshold: the record's relative error (CacheRecord::relative_error) times
// its radius over the smallest the hemisphere allows (at least 1).
float adaptive_error_score(const CacheRecord& record, const HemisphereParams& hemisphere);

class RecordPass {
 public:
  // Compiled for hemispheres of up to theta_strata rows (1 .. HEMISPHERE_MAX_THETA_STRATA). With store_strata the
  // last batch's per-stratum radiance and hit distance stay in strata() (radiance caching projects them). With a photon
  // map (--bounce-method photons) the records' rays take the bounces after the first from it (kernels/photon_map.h);
  // it must outlive the frame (photon_gather: compiled to read one, which each frame's begin_frame then names).
  RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata = false,
             const PhotonMapPass* photon_map = nullptr);
  // caustics_apart: the rays leave light -> glossy -> record to the caustic map (kernels/bounce.h
  // hit_direct_without_caustics; passes/caustic_map_pass.h), whose irradiance the frame adds at the pixels.
  RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata, bool photon_gather,
             bool caustics_apart = false);
  // Starts building the program the second constructor asks for with these arguments (GpuContext::build_ahead).
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata,
                          bool photon_gather, bool caustics_apart);
  // A new frame (a pass may be kept across frames, render/indirect.h): records start again at 0 (the array and the
  // sample buffers are kept), the ray count at 0, no light guide; bounces: the indirect bounces each record's rays
  // gather (kernels/bounce.h); photon_map: this frame's, null exactly when the pass was compiled without
  // photon_gather. A pass not begun gathers one bounce.
  void begin_frame(const PhotonMapPass* photon_map, unsigned bounces);

  // Computes records first .. first + count - 1 at the G-buffer pixels listed in candidates (a device array of pixel
  // indices); blocks until done. Throws rcsplat::Error when the hemisphere has more rows than the pass was built for.
  void compute(const GBufferView& gbuffer, const cl::Buffer& candidates, uint32_t count, uint32_t first,
               const HemisphereParams& params);
  // Adaptive rays: computes the records with `coarse` (fewer strata), then traces those whose adaptive_error_score is
  // above max_relative_error again with `full`, in place. Returns how many were traced again. Not with store_strata
  // (the strata of one batch must share one hemisphere).
  uint32_t compute_adaptive(const GBufferView& gbuffer, const cl::Buffer& candidates, uint32_t count, uint32_t first,
                            const HemisphereParams& coarse, const HemisphereParams& full, float max_relative_error);
  // Aims rays_per_record rays of every later record at these clusters (kernels/light_guide.h), beside its M x N
  // strata; no clusters or no rays: none. Records computed without a guide ignore HemisphereParams' guide fields.
  void set_light_guide(const std::vector<GuideCluster>& clusters, unsigned rays_per_record);
  const cl::Buffer& records() const { return records_; }
  // With store_strata, of the last batch: float4 (L.rgb, hit distance) per stratum, [(i * M + row) * N + column] for
  // its record i, L the share of the light the light guide leaves to the strata (such records cast no guided rays:
  // each pixel samples the guide's share, kernels/glossy.cl).
  const cl::Buffer& strata() const { return samples_; }
  uint64_t rays_cast();  // hemisphere and shadow rays cast so far
  // With a wavefront trace, the rays its last rounds traced themselves (RayQueue::traced_late; tests expect none).
  uint32_t rays_traced_late() { return rays_ ? rays_->traced_late() : 0; }
  std::vector<CacheRecord> download(size_t first, size_t count);
  // Records 0 .. records.size() - 1 become these (records kept from earlier frames: render/kept_records.h).
  void load(const std::vector<CacheRecord>& records);

 private:
  void reserve(size_t count);  // grows the array, keeping what it holds
  // Buffers for launches of `records` records of `samples_per_record` samples each; with store_strata the strata of
  // a whole batch of `batch` records.
  void reserve_samples(size_t records, size_t samples_per_record, size_t batch);
  // Traces and reduces candidates batch.first_candidate .. + batch.launch_count - 1.
  void compute_launch(const GBufferView& gbuffer, const cl::Buffer& candidates, const RecordBatchParams& batch,
                      size_t samples_per_record);
  // The wavefront trace after the hits: their first bounce's light (shade_first_hits_, its inputs set by
  // bind_inputs) with its shadow rays queued, which queues the paths going on; a stage a later bounce steps them, and
  // a last launch adds their light to their samples.
  void trace_wavefront(const std::function<NamedKernel&(NamedKernel&)>& bind_inputs, size_t items,
                       size_t launch_samples);

  GpuContext& gpu_;
  const DeviceScene& scene_;
  unsigned theta_capacity_;
  bool store_strata_;
  const PhotonMapPass* photon_map_;
  NamedKernel aim_, trace_, trace_hits_, shade_hits_, shade_first_hits_, step_paths_, finish_paths_, reduce_;
  cl::Buffer records_, ray_total_, guide_;
  bool photon_gather_;
  // Per launch: each record's guide cones, each sample's (radiance, distance) and rays cast, with a split or
  // wavefront trace (GroupSizes::record_trace) each sample's hit, and with a wavefront the queue of paths going on
  // after their first hit and its length. With store_strata, samples_ is the whole batch's strata (strata()).
  cl::Buffer record_guides_, samples_, sample_rays_, sample_hits_;
  PathQueue paths_;
  std::optional<RayQueue> rays_;  // made for the first wavefront launch (its program built only then)
  unsigned guide_clusters_ = 0, guide_rays_ = 0, bounces_ = 1;
  size_t capacity_ = 0, guide_capacity_ = 0, guides_capacity_ = 0, samples_capacity_ = 0, sample_rays_capacity_ = 0,
         sample_hits_capacity_ = 0;
};

}  // namespace rcsplat
