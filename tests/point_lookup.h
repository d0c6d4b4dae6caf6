// Kernels that read a map (photons, caustic photons, records) at query points, as the tests look them up
// (tests/pass_probe.h). One work-item a point.
#pragma once
#include <vector>

#include "cl/gpu_context.h"
#include "cl/named_kernel.h"

namespace rcsplat {

// Sets the kernel's `points` (xyz), `normals`, `point_count` and `out_name` (float4 per point), launches it and
// returns what it wrote. The kernel's other arguments must be set already, in its order before these.
std::vector<cl_float4> run_point_lookup(GpuContext& gpu, NamedKernel& kernel, const std::vector<cl_float4>& points,
                                        const std::vector<cl_float4>& normals, const char* out_name);

}  // namespace rcsplat
