// The photon map of --bounce-method photons (kernels/photon_map.cl, docs/ALGORITHM.md section 8) on the device: the grids
// the host built (cache/photon_map.h) and the lookup photons' irradiance estimates, which the record pass reads at its
// rays' hits (kernels/photon_map.h) in place of continuing their paths.
#pragma once
#include <vector>

#include "cache/photon_map.h"
#include "cl/device_scene.h"
#include "cl/gpu_context.h"

namespace rcsplat {

// The landings after the first reflection of `paths` photons from the scene's lights (passes/light_guide_pass.h), each
// landing up to `bounces` times.
std::vector<PhotonHit> shoot_reflected_photons(GpuContext& gpu, const DeviceScene& scene, unsigned paths,
                                               unsigned bounces, unsigned seed);

class PhotonMapPass {
 public:
  // Uploads the grids and estimates the irradiance at every lookup photon; blocks until done.
  PhotonMapPass(GpuContext& gpu, const PhotonMapGrids& grids);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // How the kernels bound later read the map (PhotonMapParams): record rays shorter than short_ray_paths radii
  // continue a bounce first; a lookup whose estimate summed fewer than min_support photons continues its path.
  void set_lookup(float short_ray_paths, float min_support);
  // Sets a kernel's PHOTON_MAP_ARGS (the lookup grid and its estimates).
  void bind(NamedKernel& kernel) const;
  const PhotonMapParams& params() const { return params_; }
  // The lookup photons' estimates, in the lookup grid's order, for tests: two float4 (RGB, 0) per photon, the reflected
  // light and the irradiance, both over pi (kernels/photon_map.cl).
  std::vector<cl_float4> estimates();
  // The same without the landings from PhotonMapGrids::shallow_landings on (map_shallow), for tests.
  std::vector<cl_float4> shallow_estimates();
  // The reflected-light estimate a lookup finds at these points (xyz) on surfaces facing these normals, for tests.
  std::vector<cl_float4> radiance_at(const std::vector<cl_float4>& points, const std::vector<cl_float4>& normals);

 private:
  GpuContext& gpu_;
  PhotonMapParams params_;
  cl::Buffer photons_, radiance_, shallow_, buckets_;
};

}  // namespace rcsplat
