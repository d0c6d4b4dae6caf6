#include "passes/record_pass.h"

#include <algorithm>

#include "util/error.h"

namespace rcsplat {
namespace {

// The reduction keeps one column of M strata in private memory: sizing it to M keeps that memory small.
KernelDefines record_defines(const DeviceScene& scene, unsigned theta_strata, bool store_strata, bool photon_gather,
                             bool caustics_apart) {
  if (theta_strata == 0 || theta_strata > HEMISPHERE_MAX_THETA_STRATA)
    throw Error("hemisphere: M must be between 1 and " + std::to_string(HEMISPHERE_MAX_THETA_STRATA));
  KernelDefines defines = scene.defines_with("STORE_STRATA", store_strata);
  defines["THETA_STRATA_CAPACITY"] = std::to_string(theta_strata);
  defines["PHOTON_GATHER"] = photon_gather ? "1" : "0";
  if (caustics_apart && !scene.has_specular_brdf()) throw Error("records: caustics apart in a scene without a lobe");
  defines["CAUSTICS_APART"] = caustics_apart ? "1" : "0";
  return defines;
}

}  // namespace

void RecordPass::build_ahead(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata,
                             bool photon_gather, bool caustics_apart) {
  gpu.build_ahead("records.cl", record_defines(scene, theta_strata, store_strata, photon_gather, caustics_apart));
}

RecordPass::RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata,
                       const PhotonMapPass* photon_map)
    : RecordPass(gpu, scene, theta_strata, store_strata, photon_map != nullptr) {
  photon_map_ = photon_map;
}

RecordPass::RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata,
                       bool photon_gather, bool caustics_apart)
    : gpu_(gpu),
      scene_(scene),
      theta_capacity_(theta_strata),
      store_strata_(store_strata),
      photon_map_(nullptr),
      photon_gather_(photon_gather),
      paths_(gpu, "record path queue") {
  const KernelDefines defines = record_defines(scene, theta_strata, store_strata, photon_gather, caustics_apart);
  aim_ = gpu.kernel("records.cl", "aim_record_guides", defines);
  trace_ = gpu.kernel("records.cl", "trace_record_rays", defines);
  trace_hits_ = gpu.kernel("records.cl", "trace_record_hits", defines);
  shade_hits_ = gpu.kernel("records.cl", "shade_record_hits", defines);
  shade_first_hits_ = gpu.kernel("records.cl", "shade_record_first_hits", defines);
  step_paths_ = gpu.kernel("records.cl", "step_record_paths", defines);
  finish_paths_ = gpu.kernel("records.cl", "finish_record_paths", defines);
  reduce_ = gpu.kernel("records.cl", "reduce_records", defines);
  ray_total_ = gpu_.upload(std::vector<cl_ulong>{0}, CL_MEM_READ_WRITE, "ray counter");
  // Never read while guide_clusters_ is 0.
  gpu_.upload_into(guide_, guide_capacity_, std::vector<GuideCluster>(1, GuideCluster{}), CL_MEM_READ_ONLY,
                   "light guide");
  reserve(1024);
}

void RecordPass::begin_frame(const PhotonMapPass* photon_map, unsigned bounces) {
  if ((photon_map != nullptr) != photon_gather_)
    throw Error(photon_gather_ ? "records: compiled to read a photon map, but the frame has none"
                               : "records: the frame has a photon map, but the pass was compiled without one");
  photon_map_ = photon_map;
  gpu_.queue().enqueueFillBuffer(ray_total_, cl_ulong(0), 0, sizeof(cl_ulong));
  guide_clusters_ = guide_rays_ = 0;
  bounces_ = bounces;
}

void RecordPass::set_light_guide(const std::vector<GuideCluster>& clusters, unsigned rays_per_record) {
  if (clusters.size() > GUIDE_MAX_CLUSTERS)
    throw Error("records: a light guide of " + std::to_string(clusters.size()) + " clusters (at most " +
                std::to_string(GUIDE_MAX_CLUSTERS) + ")");
  guide_clusters_ = rays_per_record ? unsigned(clusters.size()) : 0;
  guide_rays_ = guide_clusters_ ? rays_per_record : 0;
  if (guide_clusters_) gpu_.upload_into(guide_, guide_capacity_, clusters, CL_MEM_READ_ONLY, "light guide");
}

void RecordPass::reserve(size_t count) {
  gpu_.reserve<CacheRecord>(records_, capacity_, count, "irradiance records", true);
}

void RecordPass::load(const std::vector<CacheRecord>& records) {
  if (records.empty()) return;
  reserve(records.size());
  gpu_.queue().enqueueWriteBuffer(records_, CL_TRUE, 0, records.size() * sizeof(CacheRecord), records.data());
}

void RecordPass::reserve_samples(size_t records, size_t samples_per_record, size_t batch) {
  // Doubling spares a reallocation per placement level, but never past what one launch can hold: launches are
  // capped (record_samples_per_launch), so that cap bounds the samples' memory.
  const size_t most_records = std::max<size_t>(gpu_.groups().record_samples_per_launch / samples_per_record, 1);
  auto grow = [&](cl::Buffer& buffer, size_t& capacity, size_t needed, size_t element, size_t ceiling,
                  const char* what) { gpu_.reserve(buffer, capacity, needed, element, what, false, ceiling); };
  const size_t launch_samples = most_records * samples_per_record;
  grow(record_guides_, guides_capacity_, records, sizeof(RecordGuideCones), most_records, "record guide cones");
  grow(samples_, samples_capacity_, (store_strata_ ? batch : records) * samples_per_record, sizeof(cl_float4),
       store_strata_ ? batch * samples_per_record : launch_samples, store_strata_ ? "record strata" : "record samples");
  grow(sample_rays_, sample_rays_capacity_, records * samples_per_record, sizeof(cl_uint), launch_samples,
       "record samples");
  const RecordTrace shape = gpu_.groups().record_trace;
  if (shape != RecordTrace::fused)
    grow(sample_hits_, sample_hits_capacity_, records * samples_per_record, sizeof(HitDesc), launch_samples,
         "record hits");
  if (shape == RecordTrace::wavefront) {
    // Every sample of a launch may go on after its first hit (no photon map, or one thin everywhere).
    if (bounces_ > 1) paths_.reserve(records * samples_per_record, launch_samples);
    if (!rays_) rays_.emplace(gpu_, scene_, "record ray queue");
    rays_->reserve(std::min(records * samples_per_record, launch_samples), RayQueue::slots_per_hit(scene_) + 1,
                   launch_samples);
  }
}

void RecordPass::trace_wavefront(const std::function<NamedKernel&(NamedKernel&)>& bind_inputs, size_t items,
                                 size_t launch_samples) {
  paths_.clear();
  // The first hits' shading in two rounds: it lists its shadow rays, then reads their answers and queues the paths.
  rays_->run_stage(2, launch_samples, [&](cl_uint mode) {
    NamedKernel& shade = bind_inputs(shade_first_hits_)
                             .set_buffer<HitDesc>("hits", sample_hits_)
                             .set_buffer<cl_float4>("samples", samples_)
                             .set_buffer<cl_uint>("sample_rays", sample_rays_);
    rays_->bind(paths_.bind(shade), mode).launch(items, gpu_.groups().traversal);
  });
  if (bounces_ <= 1) return;  // no path goes on after its first hit
  paths_.step(
      step_paths_,
      [&](NamedKernel& step) {
        scene_.bind(step);
        if (photon_map_) photon_map_->bind(step);
      },
      bounces_ - 1, launch_samples, *rays_);
  paths_.bind(finish_paths_)
      .set_buffer<cl_float4>("samples", samples_)
      .set_buffer<cl_uint>("sample_rays", sample_rays_)
      .launch(launch_samples, gpu_.groups().per_item);
}

void RecordPass::compute_launch(const GBufferView& gbuffer, const cl::Buffer& candidates,
                                const RecordBatchParams& batch, size_t samples_per_record) {
  gbuffer.bind(aim_);
  aim_.set_buffer<cl_uint>("candidates", candidates)
      .set("batch", batch)
      .set_buffer<GuideCluster>("guide", guide_)
      .set_buffer<RecordGuideCones>("record_guides", record_guides_);
  aim_.launch(batch.launch_count, gpu_.groups().per_item);

  const size_t items = size_t(batch.launch_count) *
                       ((samples_per_record + batch.samples_per_item - 1) / batch.samples_per_item);
  // Parameters are set in the kernels' order: scene, photon map (shading only), G-buffer, the launch's inputs.
  auto bind_inputs = [&](NamedKernel& kernel, bool shades) -> NamedKernel& {
    scene_.bind(kernel);
    if (shades && photon_map_) photon_map_->bind(kernel);
    gbuffer.bind(kernel);
    return kernel.set_buffer<cl_uint>("candidates", candidates)
        .set("batch", batch)
        .set_buffer<RecordGuideCones>("record_guides", record_guides_);
  };
  const GroupSizes& groups = gpu_.groups();
  if (groups.record_trace == RecordTrace::fused) {
    bind_inputs(trace_, true)
        .set_buffer<cl_float4>("samples", samples_)
        .set_buffer<cl_uint>("sample_rays", sample_rays_)
        .launch(items, groups.traversal);
  } else {
    bind_inputs(trace_hits_, false).set_buffer<HitDesc>("hits", sample_hits_).launch(items, groups.traversal);
    if (groups.record_trace == RecordTrace::split) {
      bind_inputs(shade_hits_, true)
          .set_buffer<HitDesc>("hits", sample_hits_)
          .set_buffer<cl_float4>("samples", samples_)
          .set_buffer<cl_uint>("sample_rays", sample_rays_)
          .launch(items, groups.traversal);
    } else {
      trace_wavefront([&](NamedKernel& kernel) -> NamedKernel& { return bind_inputs(kernel, true); }, items,
                      size_t(batch.launch_count) * samples_per_record);
    }
  }

  gbuffer.bind(reduce_);
  reduce_.set_buffer<cl_uint>("candidates", candidates)
      .set("batch", batch)
      .set_buffer<cl_float4>("samples", samples_)
      .set_buffer<cl_uint>("sample_rays", sample_rays_)
      .set_buffer<CacheRecord>("records", records_)
      .set_buffer<cl_ulong>("ray_total", ray_total_);
  reduce_.launch(batch.launch_count, gpu_.groups().per_record);
}

void RecordPass::compute(const GBufferView& gbuffer, const cl::Buffer& candidates, uint32_t count, uint32_t first,
                         const HemisphereParams& params) {
  if (params.theta_strata == 0 || params.theta_strata > theta_capacity_ || params.phi_strata == 0 ||
      params.phi_strata > HEMISPHERE_MAX_PHI_STRATA)
    throw Error("records: a " + std::to_string(params.theta_strata) + "x" + std::to_string(params.phi_strata) +
                " hemisphere does not fit the record pass (built for M up to " + std::to_string(theta_capacity_) +
                ", N up to " + std::to_string(HEMISPHERE_MAX_PHI_STRATA) + ")");
  if (count == 0) return;
  reserve(size_t(first) + count);
  RecordBatchParams batch{};
  batch.hemisphere = params;
  batch.hemisphere.guide_rays = guide_rays_;
  batch.hemisphere.guide_clusters = guide_clusters_;
  batch.hemisphere.bounces = bounces_;
  batch.candidate_count = count;
  batch.first_record = first;
  batch.samples_per_item = unsigned(gpu_.groups().record_samples_per_item);
  // Records with stored strata cast no guided rays (kernels/records.cl record_sample_count).
  const size_t samples_per_record =
      size_t(params.theta_strata) * params.phi_strata + (store_strata_ ? 0u : guide_rays_);
  const size_t per_launch = std::clamp<size_t>(gpu_.groups().record_samples_per_launch / samples_per_record, 1, count);
  reserve_samples(per_launch, samples_per_record, count);
  for (size_t at = 0; at < count; at += per_launch) {
    batch.first_candidate = uint32_t(at);
    batch.launch_count = uint32_t(std::min(per_launch, count - at));
    // Stored strata keep the whole batch; otherwise each launch's samples start the buffer.
    batch.samples_first_candidate = store_strata_ ? 0u : batch.first_candidate;
    compute_launch(gbuffer, candidates, batch, samples_per_record);
  }
  gpu_.queue().finish();
}

float adaptive_error_score(const CacheRecord& record, const HemisphereParams& hemisphere) {
  // A record's noise shows as a blotch as wide as its reach: one reaching a pixel or two averages out within an 8 x 8
  // block, one reaching dozens does not. So its relative error counts in proportion to its radius over the smallest
  // radius allowed (measured on Sponza: RESULTS.md "Adaptive rays").
  double reach = double(record.radius) / (double(record.pixel_size) * hemisphere.min_radius_pixels);
  return float(double(record.relative_error) * std::max(reach, 1.0));
}

uint32_t RecordPass::compute_adaptive(const GBufferView& gbuffer, const cl::Buffer& candidates, uint32_t count,
                                      uint32_t first, const HemisphereParams& coarse, const HemisphereParams& full,
                                      float max_relative_error) {
  if (store_strata_) throw Error("records: adaptive rays need records that keep no strata");
  compute(gbuffer, candidates, count, first, coarse);
  std::vector<CacheRecord> batch = download(first, count);
  std::vector<cl_uint> uncertain_pixels;
  std::vector<uint32_t> uncertain;  // their places in the batch, in candidate order (the same bits every run)
  for (uint32_t i = 0; i < count; ++i) {
    if (!(adaptive_error_score(batch[i], full) <= max_relative_error)) {
      uncertain.push_back(i);
      uncertain_pixels.push_back(cl_uint(batch[i].pixel));
    }
  }
  if (uncertain.empty()) return 0;
  // Traced again past the batch's end, then moved into place.
  cl::Buffer again = gpu_.upload(uncertain_pixels, CL_MEM_READ_ONLY, "adaptive record candidates");
  compute(gbuffer, again, uint32_t(uncertain.size()), first + count, full);
  std::vector<CacheRecord> traced = download(size_t(first) + count, uncertain.size());
  for (size_t u = 0; u < uncertain.size(); ++u) batch[uncertain[u]] = traced[u];
  gpu_.queue().enqueueWriteBuffer(records_, CL_TRUE, size_t(first) * sizeof(CacheRecord),
                                  batch.size() * sizeof(CacheRecord), batch.data());
  return uint32_t(uncertain.size());
}

uint64_t RecordPass::rays_cast() { return gpu_.download<cl_ulong>(ray_total_, 1)[0]; }

std::vector<CacheRecord> RecordPass::download(size_t first, size_t count) {
  std::vector<CacheRecord> out(count);
  if (count)
    gpu_.queue().enqueueReadBuffer(records_, CL_TRUE, first * sizeof(CacheRecord), count * sizeof(CacheRecord),
                                   out.data());
  return out;
}

}  // namespace rcsplat
