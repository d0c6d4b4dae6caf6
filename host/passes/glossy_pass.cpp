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
      kernel_(gpu.kernel(kProgram, "glossy_indirect", defines_)) {}

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
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set("params", params).set_buffer<GuideCluster>("guide", guide_);
  bind_records(kernel_, reads);
  kernel_.set_buffer<cl_float4>("glossy_out", radiance_);
  kernel_.launch(pixels_, gpu_.groups().traversal);
  gpu_.queue().finish();
}

void GlossyPass::bind_records(NamedKernel& kernel, const GlossyCacheReads& reads) {
  if (reads.device) {
    kernel.set_buffer<CacheRecord>("world_records", *reads.device->records)
        .set_buffer<cl_uint>("world_record_starts", *reads.device->bucket_starts)
        .set_buffer<cl_uint>("world_record_lists", *reads.device->record_lists)
        .set("world_grid", reads.device->params);
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
  kernel.set_buffer<CacheRecord>("world_records", records_)
      .set_buffer<cl_uint>("world_record_starts", record_starts_)
      .set_buffer<cl_uint>("world_record_lists", record_lists_)
      .set("world_grid", read_records ? reads.grid->params : WorldRecordParams{});
}

std::vector<cl_float4> GlossyPass::cached_irradiance_at(const std::vector<CacheRecord>& records,
                                                        const WorldRecordGrid& grid,
                                                        const std::vector<cl_float4>& points,
                                                        const std::vector<cl_float4>& normals) {
  NamedKernel look_up = gpu_.kernel(kProgram, "cached_irradiance_at", defines_);
  bind_records(look_up, {&records, &grid});
  return run_point_lookup(gpu_, look_up, points, normals, "irradiance");
}

std::vector<float> GlossyPass::download_rgba() { return gpu_.download<float>(radiance_, pixels_ * 4); }

}  // namespace rcsplat
