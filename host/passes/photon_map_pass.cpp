#include "passes/photon_map_pass.h"

#include <algorithm>
#include <cstddef>

#include "passes/grid_sort_pass.h"
#include "passes/surface_patch_pass.h"
#include "util/error.h"

namespace rcsplat {
void PhotonMapPass::build_ahead(GpuContext& gpu) {
  gpu.build_ahead(kProgram);
  GridSortPass::build_ahead(gpu);
  SurfacePatchPass::build_ahead(gpu);
  PhotonLandingsPass::build_ahead(gpu);
}

DevicePhotonGrids upload_photon_grids(GpuContext& gpu, const PhotonMapGrids& grids) {
  DevicePhotonGrids d;
  d.lookup_grid = grids.lookup.params;
  d.all_grid = grids.all.params;
  d.patch_grid = grids.patches.params;
  d.shallow_landings = grids.shallow_landings;
  d.lookup_photons = gpu.upload(grids.lookup.photons, CL_MEM_READ_ONLY, "photon map");
  d.lookup_buckets = gpu.upload(grids.lookup.bucket_starts, CL_MEM_READ_ONLY, "photon map buckets");
  const std::vector<uint32_t> order = cell_order(grids.lookup);
  d.estimate_order = gpu.upload(order.empty() ? std::vector<uint32_t>{0} : order, CL_MEM_READ_ONLY,
                                "photon map estimate order");
  d.all_photons = gpu.upload(grids.all.photons, CL_MEM_READ_ONLY, "photon map");
  d.all_buckets = gpu.upload(grids.all.bucket_starts, CL_MEM_READ_ONLY, "photon map buckets");
  // The kernel reads no patch when there are none, but a buffer must be bound.
  d.patches = gpu.upload(grids.patches.patches.empty() ? std::vector<SurfacePatch>(1) : grids.patches.patches,
                         CL_MEM_READ_ONLY, "photon map surface patches");
  d.patch_buckets = gpu.upload(grids.patches.bucket_starts.empty() ? std::vector<cl_uint>(2, 0u)
                                                                  : grids.patches.bucket_starts,
                               CL_MEM_READ_ONLY, "photon map surface patch buckets");
  return d;
}

namespace {

// `count` items (Item) in `items` sorted into `grid` on the device: the sorted items and the buckets' starts.
template <class Item>
void sort_on_device(GpuContext& gpu, GridSortPass& sorter, const cl::Buffer& items, const PhotonMapParams& grid,
                    cl::Buffer& sorted, cl::Buffer& bucket_starts, const char* what) {
  static_assert(sizeof(Item) % sizeof(cl_uint) == 0 && offsetof(Item, position) == 0);
  const size_t count = grid.photon_count;  // 0 when the grid has no radius
  sorted = gpu.buffer(CL_MEM_READ_WRITE, std::max<size_t>(count, 1) * sizeof(Item), what);
  bucket_starts = gpu.buffer(CL_MEM_READ_WRITE, (size_t(grid.bucket_count) + 1) * sizeof(cl_uint), what);
  sorter.sort(items, uint32_t(sizeof(Item) / sizeof(cl_uint)), uint32_t(count), grid, sorted, bucket_starts);
}

}  // namespace

DevicePhotonGrids sort_photon_grids(GpuContext& gpu, PhotonLandingsPass& landings, double surface_area,
                                    unsigned neighbours, unsigned lookup_stride, const std::vector<glm::vec3>& triangles,
                                    int shallow_landings) {
  DevicePhotonGrids d;
  d.shallow_landings = shallow_landings;
  const uint32_t kept = landings.kept();
  const float radius = photon_gather_radius(surface_area, kept, neighbours);
  GridSortPass sorter(gpu);
  constexpr uint32_t kPhotonWords = sizeof(PhotonHit) / sizeof(cl_uint);
  d.all_grid = sorter.grid_params(landings.photons(), kPhotonWords, kept, radius);
  sort_on_device<PhotonHit>(gpu, sorter, landings.photons(), d.all_grid, d.all_photons, d.all_buckets, "photon map");

  uint32_t sparse_count = 0;
  const cl::Buffer sparse = landings.take_every(lookup_stride, sparse_count);
  d.lookup_grid = sorter.grid_params(sparse, kPhotonWords, sparse_count, radius);
  sort_on_device<PhotonHit>(gpu, sorter, sparse, d.lookup_grid, d.lookup_photons, d.lookup_buckets, "photon map");
  d.estimate_order = gpu.buffer(CL_MEM_READ_WRITE, std::max<size_t>(d.lookup_grid.photon_count, 1) * sizeof(cl_uint),
                                "photon map estimate order");
  sorter.locality_order(d.lookup_photons, kPhotonWords, d.lookup_grid.photon_count, d.lookup_grid, d.estimate_order);

  // The surface patches: cut on the device where it has doubles (the host's bits), else on the host and uploaded.
  cl::Buffer given;
  uint32_t patch_count = 0;
  if (kept && SurfacePatchPass::available(gpu)) {
    SurfacePatchPass cutter(gpu);
    given = cutter.cut(triangles, photon_patch_area(radius), patch_count);
  } else {
    std::vector<SurfacePatch> patches;
    if (kept) patches = surface_patches(triangles, photon_patch_area(radius));
    if (patches.size() > UINT32_MAX) throw Error("photon map: more than 2^32 surface patches");
    patch_count = uint32_t(patches.size());
    given = gpu.upload(patches, CL_MEM_READ_ONLY, "photon map surface patches");
  }
  constexpr uint32_t kPatchWords = sizeof(SurfacePatch) / sizeof(cl_uint);
  d.patch_grid = sorter.grid_params(given, kPatchWords, patch_count, radius);
  sort_on_device<SurfacePatch>(gpu, sorter, given, d.patch_grid, d.patches, d.patch_buckets,
                               "photon map surface patches");
  return d;
}

PhotonMapPass::PhotonMapPass(GpuContext& gpu, const DevicePhotonGrids& grids)
    : gpu_(gpu), params_(grids.lookup_grid), photons_(grids.lookup_photons), buckets_(grids.lookup_buckets) {
  // Two float4 per lookup photon: the reflected light and the irradiance (kernels/photon_map.h).
  const size_t estimate_bytes = std::max<size_t>(params_.photon_count, 1) * 2 * sizeof(cl_float4);
  radiance_ = gpu.buffer(CL_MEM_READ_WRITE, estimate_bytes, "photon map estimates");
  shallow_ = gpu.buffer(CL_MEM_READ_WRITE, estimate_bytes, "photon map shallow estimates");
  if (!params_.photon_count) return;
  NamedKernel estimate = gpu.kernel(kProgram, "estimate_photon_radiance", {});
  estimate.set_buffer<PhotonHit>("all_photons", grids.all_photons)
      .set_buffer<cl_uint>("all_buckets", grids.all_buckets)
      .set("all_grid", grids.all_grid)
      .set_buffer<SurfacePatch>("patches", grids.patches)
      .set_buffer<cl_uint>("patch_buckets", grids.patch_buckets)
      .set("patch_grid", grids.patch_grid)
      .set_buffer<PhotonHit>("map_photons", photons_)
      .set("map", params_)
      .set("shallow_landings", cl_int(grids.shallow_landings))
      .set_buffer<cl_float4>("map_radiance", radiance_)
      .set_buffer<cl_float4>("map_shallow", shallow_)
      .set_buffer<cl_uint>("estimate_order", grids.estimate_order);
  estimate.launch(params_.photon_count, gpu.groups().traversal);
  gpu.queue().finish();
}

void PhotonMapPass::set_lookup(float short_ray_paths, float min_support) {
  params_.short_path_distance = short_ray_paths * params_.radius;
  params_.min_support = min_support;
}

void PhotonMapPass::bind(NamedKernel& kernel) const {
  kernel.set_buffer<PhotonHit>("map_photons", photons_)
      .set_buffer<cl_float4>("map_radiance", radiance_)
      .set_buffer<cl_float4>("map_shallow", shallow_)
      .set_buffer<cl_uint>("map_buckets", buckets_)
      .set("map", params_);
}

}  // namespace rcsplat
