// The rough lobes' albedo table (kernels/brdf_frame.h specular_albedo), one entry per work item: read by composition
// for rough pixels and by the photon map's lookups for the surfaces record rays land on.
#include "brdf_frame.h"

__kernel void specular_albedo_table(__global float2* table) {
  uint i = get_global_id(0);
  const uint n = SPECULAR_ALBEDO_TABLE_SIZE;
  if (i >= n * n) return;
  table[i] = specular_albedo_terms((float)(i % n) / (float)(n - 1), (float)(i / n) / (float)(n - 1));
}
