// The BRDF's HSH table for radiance caching (Křivánek et al. 2005): for each material and view angle theta_o (view
// in the x-z plane), the coefficients F_k = integral of f(wo, wi) cos(theta_i) H_k(wi) over wi, so that the radiance
// reflected from incident radiance L = sum_k L_k H_k is sum_k L_k F_k. A pixel's other view azimuths follow by a
// rotation about the normal. Also the lobe's energy E = integral of (f cos)^2, which tells how much of the lobe the
// first n^2 coefficients hold (sum F_k^2 / E): too little, and the material is too sharp for that order.
// Each work item importance-samples the BRDF (kernels/brdf.h) and writes its chunk's means; the host sums the chunks
// in a fixed order.
#include "brdf.h"
#include "counter_random.h"
#include "hsh.h"
#include "shared_types.h"

__kernel void project_brdf(__global const BrdfMaterial* materials, BrdfTableParams params,
                           __global float* partial) {
  uint item = get_global_id(0);
  uint per_material = params.angle_count * params.chunk_count;
  if (item >= params.material_count * per_material) return;
  uint material = item / per_material, angle = (item % per_material) / params.chunk_count;
  const int n2 = (int)(params.order * params.order);
  __global const BrdfMaterial* m = materials + material;
  BrdfInputs in = brdf_inputs(vload3(0, m->base_color), m->metallic, m->roughness, m->specular);
  float cos_o = ((float)angle + 0.5f) / (float)params.angle_count;
  float3 wo = (float3)(sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
  float3 sums[HSH_MAX_COEFFICIENTS];
  for (int k = 0; k < n2; ++k) sums[k] = (float3)(0.0f);
  float3 energy = (float3)(0.0f);
  float basis[HSH_MAX_COEFFICIENTS];
  uint key = hash_u32(item ^ hash_u32(params.seed));
  for (uint s = 0; s < params.samples_per_chunk; ++s) {
    float3 wi;
    float pdf;
    float3 w = brdf_sample(in, wo, random01(key, s, 0u), random01(key, s, 1u), random01(key, s, 2u), &wi, &pdf);
    if (!(pdf > 0.0f)) continue;
    // E[(f cos / pdf) * f cos] = integral of (f cos)^2.
    energy += w * (w * pdf);
    hsh_basis(wi.z, atan2(wi.y, wi.x), (int)params.order, basis);
    for (int k = 0; k < n2; ++k) sums[k] += w * basis[k];
  }
  float inv = 1.0f / (float)params.samples_per_chunk;
  __global float* out = partial + (size_t)item * (size_t)(3 * n2 + 3);
  for (int k = 0; k < n2; ++k) vstore3(sums[k] * inv, k, out);
  vstore3(energy * inv, n2, out);
}
