// The path tracer's indirect light (kernels/path.cl): owns the per-pixel sums, so samples can be added in rounds.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class PathPass {
 public:
  PathPass(GpuContext& gpu, const DeviceScene& scene);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);

  // Starts over for a frame of total_samples per pixel; stratified draws them from a grid over the hemisphere.
  void begin(const GBufferView& gbuffer, unsigned total_samples, bool stratified, unsigned seed, unsigned bounces = 1);
  // Adds the next count samples to every pixel; blocks until done.
  void add_samples(unsigned count);
  unsigned samples_done() const { return done_; }

  // Indirect radiance per pixel; with variance, also the variance of that mean, per channel (one download each).
  std::vector<float> mean_rgb(std::vector<float>* variance = nullptr);
  uint64_t rays_cast();

 private:
  static constexpr const char* kProgram = "path.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  GBufferView gbuffer_;
  NamedKernel kernel_;
  cl::Buffer sum_, sum_squares_, ray_total_;
  size_t pixels_ = 0;
  unsigned total_ = 0, done_ = 0, grid_side_ = 0, seed_ = 0, bounces_ = 1;
};

}  // namespace rcsplat
