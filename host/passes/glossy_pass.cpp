#include "passes/glossy_pass.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "passes/sample_rounds.h"
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
      pixel_error_(gpu.kernel(kProgram, "glossy_pixel_error", defines_)),
      average_(gpu.kernel(kProgram, "average_glossy_chunks", defines_)),
      paths_(gpu, "glossy path queue") {}

GlossyRunStats GlossyPass::run(const GBufferView& gbuffer, unsigned samples, unsigned seed,
                               const std::vector<GuideCluster>& guide, unsigned record_strata,
                               unsigned record_guide_rays, unsigned bounces, const GlossyCacheReads& reads,
                               const GlossyFrameLight& frame_light, bool adaptive) {
  if (gbuffer.pixel_count() != pixels_ || !radiance_()) {
    pixels_ = gbuffer.pixel_count();
    const size_t bytes = std::max<size_t>(pixels_, 1) * sizeof(cl_float4);
    radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "glossy radiance");
    sums_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "glossy sums");
    moments_ = gpu_.buffer(CL_MEM_READ_WRITE, bytes, "glossy moments");
  }
  if (guide.size() > GUIDE_MAX_CLUSTERS)
    throw Error("glossy: a light guide of more than " + std::to_string(GUIDE_MAX_CLUSTERS) + " clusters");
  const unsigned sub_pixels = unsigned(gbuffer.sub_pixel_side * gbuffer.sub_pixel_side);
  // The budget in chunks per sampled sub-pixel: samples per output pixel, split among its sub-pixels.
  const double chunks_per_sub_pixel = double(samples) / double(sub_pixels * GLOSSY_CHUNK_LOBE);
  GlossyParams params{};
  params.seed = seed;
  params.guide_clusters = cl_uint(guide.size());
  params.bounces = bounces;
  if (record_strata && record_guide_rays && !guide.empty()) {
    params.record_strata = record_strata;
    params.record_guide_rays = record_guide_rays;
    params.guide_share_samples = std::max(1u, (samples + sub_pixels - 1) / sub_pixels);
  }
  // An unused one-cluster buffer when there is no guide: the kernel reads none.
  gpu_.upload_into(guide_, guide_capacity_, guide.empty() ? std::vector<GuideCluster>(1, GuideCluster{}) : guide,
                   CL_MEM_READ_ONLY, "light guide");
  if (!pixel_list_()) pixel_list_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_ONLY, "glossy pixel list");
  prepare_records(reads);
  const unsigned slots_per_chunk = GLOSSY_CHUNK_LOBE + (guide.empty() ? 0u : GLOSSY_CHUNK_GUIDED);
  GlossyRunStats stats;
  // The first round: every output pixel, one chunk each sampled sub-pixel (or, without `adaptive`, the budget's).
  params.first_chunk = 0;
  params.round_chunks = adaptive ? 1u : std::max(1u, unsigned(std::lround(chunks_per_sub_pixel)));
  params.listed = 0;
  params.slots_per_sub_pixel = std::max(params.round_chunks * slots_per_chunk, params.guide_share_samples);
  run_round(gbuffer, params, gbuffer.output_pixel_count());
  stats.most_chunks = params.round_chunks;
  std::vector<uint8_t> levels;
  // Without `adaptive` the counts stay 0 but for the rounds: the first round's sub-pixels are not counted.
  if (adaptive) levels = refinement_levels(gbuffer, frame_light, chunks_per_sub_pixel, stats);
  // Later rounds: round r doubles the chunks of the pixels whose level is r or more (2^(r-1) more each).
  const unsigned rounds = run_later_rounds(levels, [&](const std::vector<cl_uint>& listed, unsigned first, unsigned chunks) {
    gpu_.upload_into(pixel_list_, list_capacity_, listed, CL_MEM_READ_ONLY, "glossy pixel list");
    params.first_chunk = first;
    params.round_chunks = chunks;
    params.listed = 1;
    params.slots_per_sub_pixel = params.round_chunks * slots_per_chunk;
    run_round(gbuffer, params, listed.size());
    stats.most_chunks = 2 * chunks;
  });
  stats.rounds = rounds;
  average_.set_buffer<cl_float4>("glossy_sums", sums_)
      .set_buffer<cl_float4>("glossy_moments", moments_)
      .set("pixel_count", cl_uint(pixels_))
      .set_buffer<cl_float4>("glossy_out", radiance_)
      .launch(pixels_, gpu_.groups().per_item);
  gpu_.queue().finish();
  return stats;
}

std::vector<uint8_t> GlossyPass::refinement_levels(const GBufferView& gbuffer, const GlossyFrameLight& frame_light,
                                                   double chunks_per_sampled_sub_pixel, GlossyRunStats& stats) {
  const size_t output_pixels = gbuffer.output_pixel_count();
  gpu_.reserve<cl_float4>(pixel_errors_, errors_capacity_, std::max<size_t>(output_pixels, 1), "glossy pixel errors");
  const bool has_light = frame_light.direct && frame_light.irradiance;
  if (!has_light && !no_frame_light_())
    no_frame_light_ = gpu_.upload(std::vector<cl_float4>(1), CL_MEM_READ_ONLY, "glossy: no frame light");
  gbuffer.bind(pixel_error_);
  pixel_error_.set_buffer<cl_float4>("irradiance", has_light ? *frame_light.irradiance : no_frame_light_)
      .set_buffer<cl_float4>("direct", has_light ? *frame_light.direct : no_frame_light_)
      .set("frame_light", cl_uint(has_light))
      .set_buffer<cl_float4>("glossy_sums", sums_)
      .set_buffer<cl_float4>("glossy_moments", moments_)
      .set("output_pixels", cl_uint(output_pixels))
      .set_buffer<cl_float4>("error_out", pixel_errors_)
      .launch(output_pixels, gpu_.groups().per_item);
  const int side = gbuffer.sub_pixel_side;
  RoundsPlan plan = plan_rounds(gpu_.download<cl_float4>(pixel_errors_, output_pixels), gbuffer.width / side,
                                gbuffer.height / side, chunks_per_sampled_sub_pixel);
  stats.sampled_sub_pixels = plan.sampled_sub_pixels;
  stats.chunks = plan.chunks;
  stats.refined_pixels = plan.refined_pixels;
  return std::move(plan.levels);
}

void GlossyPass::run_round(const GBufferView& gbuffer, const GlossyParams& params, size_t item_count) {
  if (gpu_.groups().record_trace == RecordTrace::wavefront) {
    run_wavefront(gbuffer, params, item_count);
    return;
  }
  const size_t sub_pixels = size_t(gbuffer.sub_pixel_side * gbuffer.sub_pixel_side);
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set("params", params).set_buffer<GuideCluster>("guide", guide_);
  bind_cached_light(kernel_);
  kernel_.set_buffer<cl_uint>("pixel_list", pixel_list_)
      .set("item_count", cl_uint(item_count))
      .set_buffer<cl_float4>("glossy_sums", sums_)
      .set_buffer<cl_float4>("glossy_moments", moments_)
      .launch(item_count * sub_pixels, gpu_.groups().traversal);
}

void GlossyPass::run_wavefront(const GBufferView& gbuffer, const GlossyParams& params, size_t item_count) {
  const GroupSizes& groups = gpu_.groups();
  const size_t sub_pixels = size_t(gbuffer.sub_pixel_side * gbuffer.sub_pixel_side);
  const size_t slots_per_item = sub_pixels * params.slots_per_sub_pixel;
  const size_t launch_items = std::clamp<size_t>(groups.record_samples_per_launch / slots_per_item, 1, item_count);
  const size_t launch_slots = launch_items * slots_per_item;
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
  for (size_t first = 0; first < item_count; first += launch_items) {
    const cl_uint first_item = cl_uint(first), items = cl_uint(std::min(launch_items, item_count - first));
    const size_t slots = size_t(items) * slots_per_item, sub_pixel_items = size_t(items) * sub_pixels;
    auto set_launch = [&](NamedKernel& kernel) -> NamedKernel& {
      return kernel.set_buffer<cl_uint>("pixel_list", pixel_list_).set("first_item", first_item).set("item_count",
                                                                                                      items);
    };
    set_launch(bind_pixels(aim_)).set_buffer<cl_float4>("sample_slots", sample_slots_).launch(sub_pixel_items,
                                                                                                groups.traversal);
    scene_.bind(trace_);
    gbuffer.bind(trace_);
    trace_.set("params", params);
    set_launch(trace_)
        .set_buffer<cl_float4>("sample_slots", sample_slots_)
        .set_buffer<HitDesc>("hits", sample_hits_)
        .launch(slots, groups.traversal);
    paths_.clear();
    // The first hits' shading in two rounds: it lists its shadow rays, then reads their answers.
    rays_->run_stage(2, slots, [&](cl_uint mode) {
      scene_.bind(shade_first_hits_);
      gbuffer.bind(shade_first_hits_);
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
        .set_buffer<cl_float4>("glossy_sums", sums_)
        .set_buffer<cl_float4>("glossy_moments", moments_)
        .launch(sub_pixel_items, groups.traversal);
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

}  // namespace rcsplat
