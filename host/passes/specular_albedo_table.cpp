#include "passes/specular_albedo_table.h"

namespace rcsplat {

cl::Buffer specular_albedo_table(GpuContext& gpu, bool fill) {
  constexpr size_t kEntries = SPECULAR_ALBEDO_TABLE_SIZE * SPECULAR_ALBEDO_TABLE_SIZE;
  auto unfilled = [&] { return gpu.buffer(CL_MEM_READ_WRITE, kEntries * sizeof(cl_float2), "specular albedo table"); };
  if (!fill) return unfilled();
  // Its 4 M lobe samples cost PoCL a quarter of a second: made once per device (kept on disk), for composition and
  // the photon map and every later frame.
  return gpu.device_table("specular albedo table", "specular_albedo.cl", kEntries * sizeof(cl_float2),
                          [&](const cl::Buffer& table) {
                            NamedKernel kernel = gpu.kernel("specular_albedo.cl", "specular_albedo_table", {});
                            kernel.set_buffer<cl_float2>("table", table);
                            kernel.launch(kEntries, gpu.groups().per_item);
                          });
}

}  // namespace rcsplat
