// The photon map's surface patches cut on the device (kernels/surface_patches.cl): the host's surface_patches
// (cache/photon_map.h) bit for bit, from the triangles' corners (a tenth of the patches' bytes go up, not the
// patches). Needs double precision on the device (available()); elsewhere the host cuts them. Owns the triangles'
// corners and the per-triangle counts, kept for the next cut.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "cl/gpu_context.h"
#include "passes/scan_pass.h"

namespace rcsplat {

class SurfacePatchPass {
 public:
  explicit SurfacePatchPass(GpuContext& gpu);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);
  // Whether the device can cut them (cl_khr_fp64).
  static bool available(const GpuContext& gpu) { return gpu.device_info().fp64; }

  // The triangles (three corners each) cut as surface_patches cuts them at patch_area: a new buffer of `count`
  // SurfacePatch (one unused element when there are none). 8 bytes read back (the count).
  cl::Buffer cut(const std::vector<glm::vec3>& corners, float patch_area, uint32_t& count);

 private:
  static constexpr const char* kProgram = "surface_patches.cl";  // its kernels' file
  GpuContext& gpu_;
  ScanPass scan_;
  NamedKernel count_, write_;
  cl::Buffer corners_, counts_, firsts_, total_;
  size_t corners_capacity_ = 0, counts_capacity_ = 0, firsts_capacity_ = 0;
};

}  // namespace rcsplat
