// The BRDF's hemispherical-harmonic table (kernels/brdf_table.cl): per material and view angle, the coefficients of
// f cos over the incident directions, and how much of the lobe a given order holds. Radiance caching evaluates a
// pixel's reflected radiance as the dot product of these with a record's incident-radiance coefficients.
#pragma once
#include <vector>

#include "cl/gpu_context.h"
#include "cl/named_kernel.h"
#include "kernels/shared_types.h"

namespace rcsplat {

struct BrdfTable {
  int order = 0;        // n: n^2 coefficients a channel
  int angle_count = 0;  // view angles at cos(theta_o) = (i + 0.5) / angle_count, view in the x-z plane
  // coefficients[((material * angle_count + angle) * n^2 + k) * 3 + channel]
  std::vector<float> coefficients;
  // energy[(material * angle_count + angle) * 3 + channel]: the integral of (f cos)^2 over the hemisphere
  std::vector<float> energy;

  float coefficient(size_t material, int angle, int k, int channel) const;
  // The share of the lobe's energy the first order_used^2 coefficients hold (Parseval), in [0, 1] up to noise.
  double captured_energy(size_t material, int angle, int order_used, int channel) const;
};

class BrdfTablePass {
 public:
  explicit BrdfTablePass(GpuContext& gpu);
  // samples BRDF samples per (material, angle), split into chunks of at most 1024; deterministic for a seed.
  BrdfTable compute(const std::vector<BrdfMaterial>& materials, int order, int angle_count, unsigned samples,
                    unsigned seed = 0);

 private:
  GpuContext& gpu_;
  NamedKernel kernel_;
};

}  // namespace rcsplat
