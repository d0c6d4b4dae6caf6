#include "passes/specular_albedo_table.h"

namespace rcsplat {

cl::Buffer specular_albedo_table(GpuContext& gpu, bool fill) {
  constexpr size_t kEntries = SPECULAR_ALBEDO_TABLE_SIZE * SPECULAR_ALBEDO_TABLE_SIZE;
  cl::Buffer table = gpu.buffer(CL_MEM_READ_WRITE, kEntries * sizeof(cl_float2), "specular albedo table");
  if (fill) {
    NamedKernel kernel = gpu.kernel("specular_albedo.cl", "specular_albedo_table", {});
    kernel.set_buffer<cl_float2>("table", table);
    kernel.launch(kEntries, gpu.groups().per_item);
    gpu.queue().finish();
  }
  return table;
}

}  // namespace rcsplat
