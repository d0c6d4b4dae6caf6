// The specular lobe's hemispherical-harmonic table (kernels/brdf_table.cl): per material and view angle, the
// coefficients of the lobe's f cos over the incident directions, one vector per Fresnel term, and how much of the lobe
// a given order holds. Radiance caching evaluates a pixel's reflected radiance as the dot product of these with a
// record's incident-radiance coefficients (kernels/radiance_splat.cl).
#pragma once
#include <vector>

#include "cl/gpu_context.h"
#include "cl/named_kernel.h"
#include "kernels/shared_types.h"

namespace rcsplat {

struct BrdfTable {
  int order = 0;        // n: n^2 coefficients a term
  int angle_count = 0;  // view angles at cos(theta_o) = (i + 0.5) / angle_count, view in the x-z plane
  // lobe[((material * angle_count + angle) * 2 + term) * n^2 + k]: term 0 is A (Fresnel c0), term 1 is B (c1)
  std::vector<float> lobe;
  // energy[material * angle_count + angle]: the integral of (D V cos)^2 over the hemisphere
  std::vector<float> energy;

  float coefficient(size_t material, int angle, int term, int k) const;
  // The share of the lobe's energy the first order_used^2 coefficients hold (Parseval), in [0, 1] up to noise.
  double captured_energy(size_t material, int angle, int order_used) const;
  // The smallest share over the view angles, leaving out the most grazing bin (where cos(theta_o) < 1 / angle_count
  // a pixel's lobe is mostly below the horizon and reflects little).
  double worst_captured_energy(size_t material, int order_used) const;
};

class BrdfTablePass {
 public:
  explicit BrdfTablePass(GpuContext& gpu);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);
  // About `samples` reflections per (material, angle), in stratified chunks of 32 x 32; deterministic for a seed.
  BrdfTable compute(const std::vector<BrdfMaterial>& materials, int order, int angle_count, unsigned samples,
                    unsigned seed = 0);

 private:
  static constexpr const char* kProgram = "brdf_table.cl";  // its kernels' file
  GpuContext& gpu_;
  NamedKernel kernel_;
};

}  // namespace rcsplat
