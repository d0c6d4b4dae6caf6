// The light guide's clusters made on the device from its photons (kernels/guide_clusters.cl): the host's
// cluster_photons (cache/light_guide.h) bit for bit, without the photons leaving the device. Needs double precision
// on the device (available()); elsewhere the host makes them. Owns its scratch buffers (bins, labels, the regions'
// sums), kept for the next guide.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/grid_sort_pass.h"
#include "passes/scan_pass.h"

namespace rcsplat {

class GuideClusterPass {
 public:
  explicit GuideClusterPass(GpuContext& gpu);
  // Starts building its programs (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);
  // Whether the device can make them (cl_khr_fp64).
  static bool available(const GpuContext& gpu) { return gpu.device_info().fp64; }

  // cluster_photons(the `count` photons in `photons`, max_clusters). Reads back a 4-byte flag per round of joining
  // bins into regions (about as many rounds as a region's widest span in cells, fewer by the labels' jumps), the
  // region count and the clusters.
  std::vector<GuideCluster> cluster(const cl::Buffer& photons, uint32_t count, unsigned max_clusters);
  unsigned rounds() const { return rounds_; }  // the last cluster()'s rounds of joining

 private:
  static constexpr const char* kProgram = "guide_clusters.cl";  // its kernels' file
  GpuContext& gpu_;
  GridSortPass sorter_;
  ScanPass scan_;
  NamedKernel bin_, sum_bins_, join_, label_, sum_regions_, list_regions_, write_;
  cl::Buffer photon_bin_, photon_weight_, photon_region_, bin_starts_, bin_flux_, labels_, changed_, regions_,
      has_light_, places_, list_, clusters_;
  size_t photon_capacity_ = 0, weight_capacity_ = 0, region_capacity_ = 0;
  unsigned rounds_ = 0;
};

}  // namespace rcsplat
