#include "passes/glossy_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/point_lookup.h"
#include "util/error.h"

namespace rcsplat {
void GlossyPass::build_ahead(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable) { gpu.build_ahead(kProgram, scene.defines_with("SAMPLE_HSH_LOBES", sample_radiance_cacheable)); }

GlossyPass::GlossyPass(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable)
    : gpu_(gpu),
      scene_(scene),
      defines_(scene.defines_with("SAMPLE_HSH_LOBES", sample_radiance_cacheable)),
      kernel_(gpu.kernel(kProgram, "glossy_indirect", defines_)),
      aim_(gpu.kernel(kProgram, "aim_glossy_samples", defines_)),
      trace_(gpu.kernel(kProgram, "trace_glossy_samples", defines_)),
      shade_first_hits_(gpu.kernel(kProgram, "shade_glossy_first_hits", defines_)),
      step_paths_(gpu.kernel(kProgram, "step_glossy_paths", defines_)),
      finish_paths_(gpu.kernel(kProgram, "finish_glossy_paths", defines_)),
      gather_(gpu.kernel(kProgram, "gather_glossy_samples", defines_)),
      paths_(gpu, "glossy path queue") {}

void GlossyPass::run(const GBufferView& gbuffer, unsigned samples, unsigned seed, const std::vector<GuideCluster>& guide,
                     unsigned record_strata, unsigned record_guide_rays, unsigned bounces,
                     const GlossyCacheReads& reads) {
  if (gbuffer.pixel_count() != pixels_ || !radiance_()) {
    pixels_ = gbuffer.pixel_count();
    radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(pixels_, 1) * 4 * sizeof(float), "glossy radiance");
  }
  if (guide.size() > GUIDE_MAX_CLUSTERS)
    throw Error("glossy: a light guide of more than " + std::to_string(GUIDE_MAX_CLUSTERS) + " clusters");
  GlossyParams params{};
  params.sample_count = samples;
  params.grid_side = unsigned(std::sqrt(double(samples)));
  params.seed = seed;
  params.guide_clusters = cl_uint(guide.size());
  params.bounces = bounces;
  if (record_strata && record_guide_rays && !guide.empty()) {
    params.record_strata = record_strata;
    params.record_guide_rays = record_guide_rays;
    params.guide_share_samples = std::max(1u, samples);
  }
  // An unused one-cluster buffer when there is no guide: the kernel reads none.
  gpu_.upload_into(guide_, guide_capacity_, guide.empty() ? std::vector<GuideCluster>(1, GuideCluster{}) : guide,
                   CL_MEM_READ_ONLY, "light guide");
  prepare_records(reads);
  if (gpu_.groups().record_trace == RecordTrace::wavefront) {
    // A pixel's slots: its lobe's samples and, with a guide, half as many again aimed at it; or the guide's share.
    const size_t per_pixel = samples + (guide.empty() ? 0u : (samples + 1) / 2);
    run_wavefront(gbuffer, params, std::max<size_t>({per_pixel, params.guide_share_samples, 1}));
  } else {
    scene_.bind(kernel_);
    gbuffer.bind(kernel_);
    kernel_.set("params", params).set_buffer<GuideCluster>("guide", guide_);
    bind_cached_light(kernel_);
    kernel_.set_buffer<cl_float4>("glossy_out", radiance_);
    kernel_.launch(pixels_, gpu_.groups().traversal);
  }
  gpu_.queue().finish();
}

void GlossyPass::run_wavefront(const GBufferView& gbuffer, const GlossyParams& params, size_t slots_per_pixel) {
  const GroupSizes& groups = gpu_.groups();
  const size_t launch_pixels = std::clamp<size_t>(groups.record_samples_per_launch / slots_per_pixel, 1, pixels_);
  const size_t launch_slots = launch_pixels * slots_per_pixel;
  const cl_uint later_bounces = params.bounces > 1 ? params.bounces - 1 : 0;
  gpu_.reserve<cl_float4>(sample_slots_, slots_capacity_, launch_slots, "glossy sample slots");
  gpu_.reserve<HitDesc>(sample_hits_, hits_capacity_, launch_slots, "glossy sample hits");
  // Without later bounces the first hits queue no path: the queue stays one element.
  if (later_bounces) paths_.reserve(launch_slots, launch_slots);
  if (!rays_) rays_.emplace(gpu_, scene_, "glossy ray queue");
  rays_->reserve(launch_slots, RayQueue::slots_per_hit(scene_) + 1, launch_slots);
  // Parameters in the kernels' order: scene, G-buffer, the pass's constants and records, then the launch's.
  auto bind_pixels = [&](NamedKernel& kernel) -> NamedKernel& {
    scene_.bind(kernel);
    gbuffer.bind(kernel);
    kernel.set("params", params).set_buffer<GuideCluster>("guide", guide_);
    bind_cached_light(kernel);
    return kernel;
  };
  for (size_t first = 0; first < pixels_; first += launch_pixels) {
    const cl_uint first_pixel = cl_uint(first), pixel_count = cl_uint(std::min(launch_pixels, pixels_ - first));
    const size_t slots = size_t(pixel_count) * slots_per_pixel;
    auto set_launch = [&](NamedKernel& kernel) -> NamedKernel& {
      return kernel.set("first_pixel", first_pixel)
          .set("pixel_count", pixel_count)
          .set("slots_per_pixel", cl_uint(slots_per_pixel));
    };
    set_launch(bind_pixels(aim_)).set_buffer<cl_float4>("sample_slots", sample_slots_).launch(pixel_count,
                                                                                                groups.traversal);
    scene_.bind(trace_);
    gbuffer.bind(trace_);
    set_launch(trace_)
        .set_buffer<cl_float4>("sample_slots", sample_slots_)
        .set_buffer<HitDesc>("hits", sample_hits_)
        .launch(slots, groups.traversal);
    paths_.clear();
    // The first hits' shading in two rounds: it lists its shadow rays, then reads their answers.
    rays_->run_stage(2, slots, [&](cl_uint mode) {
      scene_.bind(shade_first_hits_);
      shade_first_hits_.set("params", params);
      bind_cached_light(shade_first_hits_);
      NamedKernel& shade = set_launch(shade_first_hits_)
                               .set_buffer<cl_float4>("sample_slots", sample_slots_)
                               .set_buffer<HitDesc>("hits", sample_hits_);
      rays_->bind(paths_.bind(shade), mode).launch(slots, groups.traversal);
    });
    paths_.step(
        step_paths_,
        [&](NamedKernel& step) {
          scene_.bind(step);
          bind_cached_light(step);
        },
        later_bounces, slots, *rays_);
    if (later_bounces)
      paths_.bind(finish_paths_).set_buffer<cl_float4>("sample_slots", sample_slots_).launch(slots, groups.per_item);
    set_launch(bind_pixels(gather_))
        .set_buffer<cl_float4>("sample_slots", sample_slots_)
        .set_buffer<cl_float4>("glossy_out", radiance_)
        .launch(pixel_count, groups.traversal);
  }
}

void GlossyPass::bind_records(NamedKernel& kernel) {
  kernel.set_buffer<CacheRecord>("world_records", *bound_records_)
      .set_buffer<cl_uint>("world_record_starts", *bound_starts_)
      .set_buffer<cl_uint>("world_record_lists", *bound_lists_)
      .set("world_grid", bound_grid_);
}

void GlossyPass::bind_cached_light(NamedKernel& kernel) {
  bind_records(kernel);
  if (bound_caustics_) {
    bound_caustics_->bind(kernel);
    return;
  }
  if (!no_caustic_photons_()) {
    no_caustic_photons_ = gpu_.upload(std::vector<PhotonHit>(1), CL_MEM_READ_ONLY, "glossy: no caustic map");
    no_caustic_buckets_ = gpu_.upload(std::vector<cl_uint>{0, 0}, CL_MEM_READ_ONLY, "glossy: no caustic map");
  }
  kernel.set_buffer<PhotonHit>("caustic_photons", no_caustic_photons_)
      .set_buffer<cl_uint>("caustic_buckets", no_caustic_buckets_)
      .set("caustic_grid", PhotonMapParams{});
}

void GlossyPass::prepare_records(const GlossyCacheReads& reads) {
  bound_caustics_ = reads.caustics;
  if (reads.device) {
    bound_records_ = reads.device->records;
    bound_starts_ = reads.device->bucket_starts;
    bound_lists_ = reads.device->record_lists;
    bound_grid_ = reads.device->params;
    return;
  }
  // No records: an empty grid (record_count 0), which the kernel never reads past its parameters.
  const bool read_records = reads.records && reads.grid && reads.grid->params.record_count > 0 &&
                            reads.grid->params.record_count == reads.records->size();
  gpu_.upload_into(records_, records_capacity_, read_records ? *reads.records : std::vector<CacheRecord>(1),
                   CL_MEM_READ_ONLY, "glossy: records");
  gpu_.upload_into(record_starts_, starts_capacity_,
                   read_records ? reads.grid->bucket_starts : std::vector<uint32_t>{0, 0}, CL_MEM_READ_ONLY,
                   "glossy: record grid");
  gpu_.upload_into(record_lists_, lists_capacity_,
                   read_records && !reads.grid->record_lists.empty() ? reads.grid->record_lists
                                                                     : std::vector<uint32_t>{0},
                   CL_MEM_READ_ONLY, "glossy: record grid");
  bound_records_ = &records_;
  bound_starts_ = &record_starts_;
  bound_lists_ = &record_lists_;
  bound_grid_ = read_records ? reads.grid->params : WorldRecordParams{};
}

std::vector<cl_float4> GlossyPass::cached_irradiance_at(const std::vector<CacheRecord>& records,
                                                        const WorldRecordGrid& grid,
                                                        const std::vector<cl_float4>& points,
                                                        const std::vector<cl_float4>& normals) {
  NamedKernel look_up = gpu_.kernel(kProgram, "cached_irradiance_at", defines_);
  prepare_records({&records, &grid});
  bind_records(look_up);
  return run_point_lookup(gpu_, look_up, points, normals, "irradiance");
}

std::vector<float> GlossyPass::download_rgba() { return gpu_.download<float>(radiance_, pixels_ * 4); }

}  // namespace rcsplat
