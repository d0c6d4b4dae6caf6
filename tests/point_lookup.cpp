#include "point_lookup.h"

#include <algorithm>

namespace rcsplat {

std::vector<cl_float4> run_point_lookup(GpuContext& gpu, NamedKernel& kernel, const std::vector<cl_float4>& points,
                                        const std::vector<cl_float4>& normals, const char* out_name) {
  cl::Buffer p = gpu.upload(points, CL_MEM_READ_ONLY, "lookup points");
  cl::Buffer n = gpu.upload(normals, CL_MEM_READ_ONLY, "lookup normals");
  cl::Buffer out = gpu.buffer(CL_MEM_READ_WRITE, std::max<size_t>(points.size(), 1) * sizeof(cl_float4), "lookups");
  kernel.set_buffer<cl_float4>("points", p)
      .set_buffer<cl_float4>("normals", n)
      .set("point_count", cl_uint(points.size()))
      .set_buffer<cl_float4>(out_name, out);
  kernel.launch(points.size(), gpu.groups().traversal);
  return gpu.download<cl_float4>(out, points.size());
}

}  // namespace rcsplat
