#include "passes/surface_patch_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "kernels/shared_types.h"
#include "util/error.h"

namespace rcsplat {
void SurfacePatchPass::build_ahead(GpuContext& gpu) {
  if (!available(gpu)) return;
  gpu.build_ahead(kProgram);
  ScanPass::build_ahead(gpu);
}

SurfacePatchPass::SurfacePatchPass(GpuContext& gpu)
    : gpu_(gpu),
      scan_(gpu),
      count_(gpu.kernel(kProgram, "count_triangle_patches")),
      write_(gpu.kernel(kProgram, "write_triangle_patches")) {
  total_ = gpu.buffer(CL_MEM_READ_WRITE, sizeof(cl_ulong), "photon map surface patches");
}

cl::Buffer SurfacePatchPass::cut(const std::vector<glm::vec3>& corners, float patch_area, uint32_t& count) {
  count = 0;
  const size_t triangles = corners.size() / 3;
  if (!(patch_area > 0.0f) || !std::isfinite(patch_area) || triangles == 0 || triangles >= UINT32_MAX)  // none
    return gpu_.buffer(CL_MEM_READ_WRITE, sizeof(SurfacePatch), "photon map surface patches");
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  gpu_.reserve<glm::vec3>(corners_, corners_capacity_, corners.size(), "photon map surface patches");
  gpu_.queue().enqueueWriteBuffer(corners_, CL_FALSE, 0, corners.size() * sizeof(glm::vec3), corners.data());
  gpu_.reserve<cl_uint>(counts_, counts_capacity_, triangles + 1, "photon map surface patches");
  gpu_.reserve<cl_uint>(firsts_, firsts_capacity_, triangles + 1, "photon map surface patches");
  gpu_.queue().enqueueFillBuffer(counts_, cl_uint(0), triangles * sizeof(cl_uint), sizeof(cl_uint));
  gpu_.queue().enqueueFillBuffer(total_, cl_ulong(0), 0, sizeof(cl_ulong));
  const size_t group = gpu_.groups().per_item;
  // Both kernels start with the triangles and the patch area.
  auto bind_triangles = [&](NamedKernel& kernel) -> NamedKernel& {
    return kernel.set_buffer<cl_float>("corners", corners_)
        .set("triangle_count", cl_uint(triangles))
        .set("patch_area", cl_float(patch_area));
  };
  bind_triangles(count_)
      .set_buffer<cl_uint>("counts", counts_)
      .set_buffer<cl_ulong>("total", total_);
  count_.launch(triangles, group);
  const cl_ulong total = gpu_.download<cl_ulong>(total_, 1)[0];
  // The scan and the patches' places are 32-bit; a scene needs far fewer (about 128 per photon over the map's
  // neighbours, and two per small triangle).
  if (total > cl_ulong(UINT32_MAX) / 2)
    throw Error("photon map: " + std::to_string(total) + " surface patches, more than 2^31");
  scan_.exclusive(counts_, uint32_t(triangles + 1), firsts_);
  count = uint32_t(total);
  cl::Buffer patches = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(count, 1) * sizeof(SurfacePatch),
                                   "photon map surface patches");
  bind_triangles(write_)
      .set_buffer<cl_uint>("firsts", firsts_)
      .set_buffer<SurfacePatch>("patches", patches);
  write_.launch(triangles, group);
  return patches;
}

}  // namespace rcsplat
