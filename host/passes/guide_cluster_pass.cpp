#include "passes/guide_cluster_pass.h"

#include <algorithm>

namespace rcsplat {
namespace {

// The guide's bins and the doubles of a region's sums (kernels/shared_types.h).
constexpr uint32_t kBinCount = GUIDE_BIN_COUNT;
constexpr size_t kRegionDoubles = GUIDE_REGION_DOUBLES;

}  // namespace

void GuideClusterPass::build_ahead(GpuContext& gpu) {
  if (!available(gpu)) return;
  gpu.build_ahead(kProgram);
  GridSortPass::build_ahead(gpu);
  ScanPass::build_ahead(gpu);
}

GuideClusterPass::GuideClusterPass(GpuContext& gpu)
    : gpu_(gpu),
      sorter_(gpu),
      scan_(gpu),
      bin_(gpu.kernel(kProgram, "bin_guide_photons")),
      sum_bins_(gpu.kernel(kProgram, "sum_guide_bins")),
      join_(gpu.kernel(kProgram, "join_guide_bins")),
      label_(gpu.kernel(kProgram, "label_guide_photons")),
      sum_regions_(gpu.kernel(kProgram, "sum_guide_regions")),
      list_regions_(gpu.kernel(kProgram, "list_guide_regions")),
      write_(gpu.kernel(kProgram, "write_guide_clusters")) {
  const char* what = "light guide clusters";
  bin_starts_ = gpu.buffer(CL_MEM_READ_WRITE, (kBinCount + 2) * sizeof(cl_uint), what);
  bin_flux_ = gpu.buffer(CL_MEM_READ_WRITE, kBinCount * sizeof(cl_double), what);
  labels_ = gpu.buffer(CL_MEM_READ_WRITE, kBinCount * sizeof(cl_uint), what);
  changed_ = gpu.buffer(CL_MEM_READ_WRITE, sizeof(cl_uint), what);
  regions_ = gpu.buffer(CL_MEM_READ_WRITE, kBinCount * kRegionDoubles * sizeof(cl_double), what);
  has_light_ = gpu.buffer(CL_MEM_READ_WRITE, (kBinCount + 1) * sizeof(cl_uint), what);
  places_ = gpu.buffer(CL_MEM_READ_WRITE, (kBinCount + 1) * sizeof(cl_uint), what);
  list_ = gpu.buffer(CL_MEM_READ_WRITE, kBinCount * sizeof(cl_uint), what);
  clusters_ = gpu.buffer(CL_MEM_READ_WRITE, GUIDE_MAX_CLUSTERS * sizeof(GuideCluster), what);
}

std::vector<GuideCluster> GuideClusterPass::cluster(const cl::Buffer& photons, uint32_t count, unsigned max_clusters) {
  rounds_ = 0;
  max_clusters = std::min<unsigned>(max_clusters, GUIDE_MAX_CLUSTERS);
  if (count == 0 || max_clusters == 0) return {};
  const char* what = "light guide clusters";
  const size_t group = gpu_.groups().per_item;
  gpu_.reserve<cl_uint>(photon_bin_, photon_capacity_, count, what);
  gpu_.reserve<cl_double>(photon_weight_, weight_capacity_, count, what);
  gpu_.reserve<cl_uint>(photon_region_, region_capacity_, count, what);
  bin_.set_buffer<PhotonHit>("photons", photons)
      .set("photon_count", count)
      .set_buffer<cl_uint>("photon_bin", photon_bin_)
      .set_buffer<cl_double>("photon_weight", photon_weight_)
      .launch(count, group);
  // The photons without a bin go to the last bucket, which no bin reads.
  const cl::Buffer& by_bin = sorter_.order_by_bucket(photon_bin_, count, kBinCount + 1, bin_starts_);
  sum_bins_.set_buffer<cl_uint>("order", by_bin)
      .set_buffer<cl_uint>("bin_starts", bin_starts_)
      .set_buffer<cl_double>("photon_weight", photon_weight_)
      .set_buffer<cl_double>("bin_flux", bin_flux_)
      .set_buffer<cl_uint>("labels", labels_)
      .launch(kBinCount, group);
  for (cl_uint changed = 1; changed; ++rounds_) {
    gpu_.queue().enqueueFillBuffer(changed_, cl_uint(0), 0, sizeof(cl_uint));
    join_.set_buffer<cl_double>("bin_flux", bin_flux_)
        .set_buffer<cl_uint>("labels", labels_)
        .set_buffer<cl_uint>("changed", changed_)
        .launch(kBinCount, group);
    changed = gpu_.download<cl_uint>(changed_, 1)[0];
  }
  label_.set_buffer<cl_uint>("photon_bin", photon_bin_)
      .set("photon_count", count)
      .set_buffer<cl_uint>("labels", labels_)
      .set_buffer<cl_uint>("photon_region", photon_region_)
      .launch(count, group);
  const cl::Buffer& by_region = sorter_.order_by_bucket(photon_region_, count, kBinCount + 1, bin_starts_);
  gpu_.queue().enqueueFillBuffer(has_light_, cl_uint(0), kBinCount * sizeof(cl_uint), sizeof(cl_uint));
  sum_regions_.set_buffer<PhotonHit>("photons", photons)
      .set_buffer<cl_double>("photon_weight", photon_weight_)
      .set_buffer<cl_uint>("order", by_region)
      .set_buffer<cl_uint>("region_starts", bin_starts_)
      .set_buffer<cl_double>("regions", regions_)
      .set_buffer<cl_uint>("has_light", has_light_)
      .launch(kBinCount, group);
  scan_.exclusive(has_light_, kBinCount + 1, places_);
  cl_uint region_count = 0;
  gpu_.queue().enqueueReadBuffer(places_, CL_TRUE, kBinCount * sizeof(cl_uint), sizeof(cl_uint), &region_count);
  list_regions_.set_buffer<cl_uint>("has_light", has_light_)
      .set_buffer<cl_uint>("places", places_)
      .set_buffer<cl_uint>("list", list_)
      .launch(kBinCount, group);
  write_.set_buffer<cl_double>("regions", regions_)
      .set_buffer<cl_uint>("list", list_)
      .set("region_count", region_count)
      .set("max_clusters", cl_uint(max_clusters))
      .set_buffer<GuideCluster>("clusters", clusters_)
      .launch(region_count, group);
  return gpu_.download<GuideCluster>(clusters_, std::min<size_t>(region_count, max_clusters));
}

}  // namespace rcsplat
