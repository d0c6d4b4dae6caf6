#include "passes/record_pass.h"

#include <algorithm>

#include "util/error.h"

namespace rcsplat {
namespace {

// The kernel keeps one column of M strata in private memory: sizing it to M keeps that memory small.
KernelDefines record_defines(const DeviceScene& scene, unsigned theta_strata, bool store_strata, bool photon_gather) {
  if (theta_strata == 0 || theta_strata > HEMISPHERE_MAX_THETA_STRATA)
    throw Error("hemisphere: M must be between 1 and " + std::to_string(HEMISPHERE_MAX_THETA_STRATA));
  KernelDefines defines = scene.defines_with("STORE_STRATA", store_strata);
  defines["THETA_STRATA_CAPACITY"] = std::to_string(theta_strata);
  defines["PHOTON_GATHER"] = photon_gather ? "1" : "0";
  return defines;
}

}  // namespace

RecordPass::RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata, bool store_strata,
                       const PhotonMapPass* photon_map)
    : gpu_(gpu),
      scene_(scene),
      theta_capacity_(theta_strata),
      store_strata_(store_strata),
      photon_map_(photon_map),
      kernel_(gpu.kernel("records.cl", "compute_records",
                         record_defines(scene, theta_strata, store_strata, photon_map != nullptr))) {
  ray_total_ = gpu_.upload(std::vector<cl_ulong>{0}, CL_MEM_READ_WRITE, "ray counter");
  guide_ = gpu_.upload(std::vector<GuideCluster>(1, GuideCluster{}), CL_MEM_READ_ONLY, "light guide");  // never read while guide_clusters_ is 0
  reserve(1024);
}

void RecordPass::set_light_guide(const std::vector<GuideCluster>& clusters, unsigned rays_per_record) {
  if (clusters.size() > GUIDE_MAX_CLUSTERS)
    throw Error("records: a light guide of " + std::to_string(clusters.size()) + " clusters (at most " +
                std::to_string(GUIDE_MAX_CLUSTERS) + ")");
  guide_clusters_ = rays_per_record ? unsigned(clusters.size()) : 0;
  guide_rays_ = guide_clusters_ ? rays_per_record : 0;
  if (guide_clusters_) guide_ = gpu_.upload(clusters, CL_MEM_READ_ONLY, "light guide");
}

void RecordPass::reserve(size_t count) {
  if (count <= capacity_) return;
  size_t grown = std::max(count, capacity_ * 2);
  cl::Buffer bigger = gpu_.buffer(CL_MEM_READ_WRITE, grown * sizeof(CacheRecord), "irradiance records");
  if (capacity_) gpu_.queue().enqueueCopyBuffer(records_, bigger, 0, 0, capacity_ * sizeof(CacheRecord));
  records_ = bigger;
  capacity_ = grown;
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
  scene_.bind(kernel_);
  if (photon_map_) photon_map_->bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set_buffer<cl_uint>("candidates", candidates)
      .set("batch", batch)
      .set_buffer<CacheRecord>("records", records_)
      .set_buffer<GuideCluster>("guide", guide_)
      .set_buffer<cl_ulong>("ray_total", ray_total_);
  if (store_strata_) {
    size_t strata = size_t(count) * params.theta_strata * params.phi_strata;
    if (strata > strata_capacity_) {
      strata_capacity_ = std::max(strata, strata_capacity_ * 2);
      strata_ = gpu_.buffer(CL_MEM_READ_WRITE, strata_capacity_ * sizeof(cl_float4), "record strata");
    }
    kernel_.set_buffer<cl_float4>("strata", strata_);
  }
  kernel_.launch(count, gpu_.groups().per_record);
  gpu_.queue().finish();
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
