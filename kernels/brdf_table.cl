// The specular lobe's HSH table for radiance caching (Křivánek et al. 2005): for each material and view angle theta_o
// (view in the x-z plane), the coefficients of the lobe's f cos over the incident directions, split by Fresnel term:
// the lobe is (c0 + c1 (1 - v.h)^5) D V (kernels/brdf.h specular_fresnel_terms), so
//   A_k = integral of D V cos(theta_i) H_k(wi),   B_k = integral of (1 - v.h)^5 D V cos(theta_i) H_k(wi),
// and a pixel reflects sum_k lambda_k (c0 A_k + c1 B_k) of incident radiance lambda, with its own c0 and c1 (base
// colour textures and metallic textures stay per pixel). Only the roughness shapes A and B. Also the lobe's energy
// integral of (D V cos)^2, which tells how much of the lobe the first n^2 coefficients hold (Parseval): too little at
// the highest order, and the lobe is too sharp to cache. The sin(m phi) coefficients vanish (the lobe is symmetric
// about the x-z plane) and come out as noise.
// Each work item draws a stratified grid of reflections about the GGX lobe's visible normals (Heitz 2018) and writes
// its chunk's means; the host sums the chunks in a fixed order.
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
  float alpha = fmax(materials[material].roughness * materials[material].roughness, MIN_GGX_ALPHA), a2 = alpha * alpha;
  float cos_o = ((float)angle + 0.5f) / (float)params.angle_count;
  float3 wo = (float3)(sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
  float2 sums[HSH_MAX_COEFFICIENTS];
  for (int k = 0; k < n2; ++k) sums[k] = (float2)(0.0f);
  float energy = 0.0f;
  float basis[HSH_MAX_COEFFICIENTS];
  uint key = hash_u32(item ^ hash_u32(params.seed));
  const uint side = (uint)sqrt((float)params.samples_per_chunk);
  for (uint s = 0; s < side * side; ++s) {
    float u1 = ((float)(s % side) + random01(key, s, 0u)) / (float)side;
    float u2 = ((float)(s / side) + random01(key, s, 1u)) / (float)side;
    float3 h = ggx_sample_visible_normal(wo, alpha, u1, u2);
    float3 wi = 2.0f * dot(wo, h) * h - wo;
    if (wi.z <= 0.0f) continue;
    // D V cos / pdf = G2 / G1 for a reflection through the visible normals; E[(D V cos / pdf) (D V cos)] is the
    // energy.
    float weight = ggx_g2_over_g1(wi.z, wo.z, a2);
    float fw = schlick_weight(fmax(dot(wo, h), 0.0f));
    energy += weight * ggx_d(h, a2) * ggx_visibility(wi.z, wo.z, a2) * wi.z;
    hsh_basis(wi.z, atan2(wi.y, wi.x), (int)params.order, basis);
    for (int k = 0; k < n2; ++k) sums[k] += (float2)(weight, weight * fw) * basis[k];
  }
  float inv = 1.0f / (float)(side * side);
  __global float* out = partial + (size_t)item * (size_t)(2 * n2 + 1);
  for (int k = 0; k < n2; ++k) {
    out[k] = sums[k].x * inv;
    out[n2 + k] = sums[k].y * inv;
  }
  out[2 * n2] = energy * inv;
}
