// Direct light (kernels/direct.cl): owns the direct-radiance image.
#pragma once
#include <cstdint>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

// How a run spent its light samples (area lights and the environment's peak).
struct DirectRunStats {
  unsigned rounds = 0;          // 0: one pass, strata_per_axis^2 samples in every sub-pixel
  uint64_t samples = 0;         // in rounds: the samples taken, every round
  uint64_t sampled_sub_pixels = 0;
  uint64_t refined_pixels = 0;  // output pixels that took a round after the first
};

class DirectPass {
 public:
  DirectPass(GpuContext& gpu, const DeviceScene& scene);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);
  // strata_per_axis^2 stratified samples on the emissive triangles (and the environment's peak) per sub-pixel; seed
  // varies the sample pattern. With light_budget > 0, in a scene that samples lights, the samples come in rounds
  // instead: light_budget per output pixel on average, one a sub-pixel first, then doublings where the neighbours'
  // samples estimate the most error (passes/sample_rounds.h).
  DirectRunStats run(const GBufferView& gbuffer, unsigned strata_per_axis, unsigned seed, unsigned light_budget = 0);
  // float4 per pixel: reflected direct radiance RGB, A = shadow rays the pixel cast.
  const cl::Buffer& radiance() const { return radiance_; }

 private:
  static constexpr const char* kProgram = "direct.cl";  // its kernels' file
  bool samples_lights() const;  // area lights or an environment peak: the rounds' kernels are compiled
  DirectRunStats run_rounds(const GBufferView& gbuffer, unsigned seed, unsigned light_budget);
  void run_round(const GBufferView& gbuffer, const DirectParams& params, size_t item_count);

  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_, round_, pixel_error_, average_;
  cl::Buffer radiance_;
  // In rounds: per sub-pixel the samples' sums and moments (kernels/direct.cl); per output pixel the error estimate;
  // a later round's list of output pixels.
  cl::Buffer sums_, moments_, pixel_errors_, pixel_list_;
  size_t pixels_ = 0, errors_capacity_ = 0, list_capacity_ = 0;
};

}  // namespace rcsplat
