// The rough specular lobes' directional albedo table (kernels/specular_albedo.cl, kernels/brdf_frame.h), shared by
// composition (rough pixels) and the photon map's lookups (the surfaces record rays land on).
#pragma once
#include "cl/gpu_context.h"

namespace rcsplat {

// A buffer of SPECULAR_ALBEDO_TABLE_SIZE^2 float2 entries, filled on the device when `fill` (a scene with a specular
// lobe), once per GpuContext and kept on disk per device (GpuContext::device_table); otherwise a new buffer left
// unfilled: kernels compiled without HAS_SPECULAR_BRDF never read it. Blocks until done.
cl::Buffer specular_albedo_table(GpuContext& gpu, bool fill);

}  // namespace rcsplat
