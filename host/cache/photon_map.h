// The photon map of --bounce-method photons, as the host builds it from the photons' landings (passes/photon_map_pass.h
// shoots them and uploads the result): the landings after the first reflection, sorted into the buckets of a hashed
// grid (kernels/photon_grid.h), and a sparser grid of every few of them, which carry the radiance estimates that
// lookups return (Christensen 1999: the estimate uses every photon, the lookup searches few).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/shared_types.h"

namespace rcsplat {

struct PhotonGrid {
  PhotonMapParams params{};
  std::vector<PhotonHit> photons;       // sorted by bucket
  std::vector<uint32_t> bucket_starts;  // params.bucket_count + 1: bucket h holds [starts[h], starts[h + 1])
};

struct PatchGrid {
  PhotonMapParams params{};
  std::vector<SurfacePatch> patches;    // sorted by bucket
  std::vector<uint32_t> bucket_starts;  // as PhotonGrid's
};

struct PhotonMapGrids {
  PhotonGrid all;     // every photon kept: the density estimates sum over it
  PhotonGrid lookup;  // every lookup_stride-th of them: where the estimates are made and what lookups search
  // The shallow estimates (map_shallow) count the photons of landings below this: with N bounces, N - 1 leaves out
  // the last landing, so that a path continued one bounce past a short ray reads bounces 3 .. N there (0: none).
  int shallow_landings = 0;
  // The scene's surface in patches, sorted into a grid of the same radius: an estimate divides by the area of facing
  // surface in its disc (kernels/photon_map.cl). Empty: every disc is taken as full, pi r^2.
  PatchGrid patches;
};

// The density estimate's radius: the disc that holds `neighbours` photons on average when `photons` photons spread over
// `surface_area` (device units).
float photon_gather_radius(double surface_area, size_t photons, unsigned neighbours);

// The grid sort_into_grid sorts items into: one radius and a hair wide, twice as many buckets as items (a power of
// two), its origin a cell below the lowest item. No radius (no surface to spread over): no items.
PhotonMapParams photon_grid_params(const std::vector<PhotonHit>& photons, float radius);
// The same from the items' count and their lowest coordinate on each axis.
PhotonMapParams photon_grid_params(size_t items, const std::array<float, 3>& lowest, float radius);
PhotonMapParams photon_grid_params(const std::vector<SurfacePatch>& patches, float radius);

// photons (patches) sorted into a grid of cells one radius wide (and a hair more, so rounding never hides one within
// the radius); the order within a cell is the order given.
PhotonGrid sort_into_grid(const std::vector<PhotonHit>& photons, float radius);
PatchGrid sort_into_grid(const std::vector<SurfacePatch>& patches, float radius);

// The grid's photons (indices into grid.photons) in the Morton order of their cells: a kernel that visits each
// photon's neighbourhood in this order has consecutive work-items read the same cells, where the bucket order
// (hashed) scatters them over the whole map.
std::vector<uint32_t> cell_order(const PhotonGrid& grid);

// The area of a surface patch for a density estimate of this radius: PHOTON_PATCHES_PER_DISC to a full disc.
float photon_patch_area(float radius);

// Every triangle (positions, three per triangle) cut into n x n equal sub-triangles of area at most patch_area (n at
// most 256), each a patch at its centroid, once per side (the normal and its opposite).
std::vector<SurfacePatch> surface_patches(const std::vector<glm::vec3>& positions, float patch_area);

// The landings that hit a surface with some flux arriving.
std::vector<PhotonHit> lit_landings(const std::vector<PhotonHit>& photons);

// Both grids over the kept landings, radius as photon_gather_radius gives it for their count, and with the scene's
// triangles (device positions, three per triangle; none: no patches) their patches, PHOTON_PATCHES_PER_DISC per disc.
PhotonMapGrids build_photon_map(const std::vector<PhotonHit>& kept, double surface_area, unsigned neighbours,
                                unsigned lookup_stride, const std::vector<glm::vec3>& triangles = {});

}  // namespace rcsplat
