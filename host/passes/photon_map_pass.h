// The photon map of --bounce-method photons (kernels/photon_map.cl, docs/ALGORITHM.md section 8) on the device: the grids
// the host built (cache/photon_map.h) and the lookup photons' irradiance estimates, which the record pass reads at its
// rays' hits (kernels/photon_map.h) in place of continuing their paths.
#pragma once
#include <vector>

#include "cache/photon_map.h"
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "util/test_probe.h"
#include "passes/photon_landings_pass.h"

namespace rcsplat {

// The photon map's grids on the device: the lookup photons' grid (every few photons, which carry the estimates), every
// photon's and the surface patches', and the order the estimates are made in (a lookup photon's number at each place:
// neighbours in space together; any order gives the same estimates).
struct DevicePhotonGrids {
  PhotonMapParams lookup_grid{}, all_grid{}, patch_grid{};
  cl::Buffer lookup_photons, lookup_buckets, all_photons, all_buckets, patches, patch_buckets;
  cl::Buffer estimate_order;
  int shallow_landings = 0;  // PhotonMapGrids::shallow_landings
};

// The host's grids uploaded.
DevicePhotonGrids upload_photon_grids(GpuContext& gpu, const PhotonMapGrids& grids);
// build_photon_map's grids over the photons `landings` keeps, built on the device (passes/grid_sort_pass.h): the same
// bits as the host's, and the estimates' order (GridSortPass::locality_order). No photon or patch comes back; the
// surface patches are cut on the device where it has doubles (SurfacePatchPass), else on the host.
DevicePhotonGrids sort_photon_grids(GpuContext& gpu, PhotonLandingsPass& landings, double surface_area,
                                    unsigned neighbours, unsigned lookup_stride, const std::vector<glm::vec3>& triangles,
                                    int shallow_landings);

class PhotonMapPass {
 public:
  // Estimates the irradiance at every lookup photon; blocks until done.
  PhotonMapPass(GpuContext& gpu, const DevicePhotonGrids& grids);
  PhotonMapPass(GpuContext& gpu, const PhotonMapGrids& grids) : PhotonMapPass(gpu, upload_photon_grids(gpu, grids)) {}
  // Starts building its programs (GpuContext::build_ahead) with the switches the constructor and sort_photon_grids
  // will ask for.
  static void build_ahead(GpuContext& gpu);

  // How the kernels bound later read the map (PhotonMapParams): record rays shorter than short_ray_paths radii
  // continue a bounce first; a lookup whose estimate summed fewer than min_support photons continues its path.
  void set_lookup(float short_ray_paths, float min_support);
  // Sets a kernel's PHOTON_MAP_ARGS (the lookup grid and its estimates).
  void bind(NamedKernel& kernel) const;
  const PhotonMapParams& params() const { return params_; }

 private:
  friend struct test::PassProbe;  // the lookup photons' estimates (tests/pass_probe.h)
  static constexpr const char* kProgram = "photon_map.cl";  // its kernels' file
  GpuContext& gpu_;
  PhotonMapParams params_;
  cl::Buffer photons_, radiance_, shallow_, buckets_;
};

}  // namespace rcsplat
