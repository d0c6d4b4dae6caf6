// The splat and normalisation (kernels/splat.cl): owns the fixed-point accumulation buffers and the resolved
// irradiance (ComposePass makes the pixels' light of it).
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class SplatPass {
 public:
  explicit SplatPass(GpuContext& gpu);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // Clears the sums and splats records 0 .. count - 1 at accuracy a, at the frame's fixed-point scale; blocks until
  // done.
  void splat_all(const GBufferView& gbuffer, const cl::Buffer& records, uint32_t count, float accuracy);
  // Divides: the irradiance per pixel.
  void resolve(const GBufferView& gbuffer);
  // After resolve: pixels with geometry that no record reached take the best-weighted record sitting within `window`
  // pixels (record_at_pixel: placement's map, -1 where none sits); returns how many did (kernels/splat.cl).
  uint32_t fill_uncovered(const GBufferView& gbuffer, const cl::Buffer& records, const cl::Buffer& record_at_pixel,
                          int window);

  const cl::Buffer& irradiance() const { return irradiance_; }  // float4: E.rgb, sum w
  std::vector<float> irradiance_rgbw();
  std::vector<uint32_t> records_per_pixel();
  const cl::Buffer& records_per_pixel_buffer() const { return counts_; }  // uint: records reaching each pixel

 private:
  static constexpr const char* kProgram = "splat.cl";  // its kernels' file
  GpuContext& gpu_;
  NamedKernel clear_, max_irradiance_, splat_, resolve_, fill_;
  cl::Buffer sums_, counts_, max_bits_, filled_, irradiance_;
  SplatParams params_{};
  size_t pixels_ = 0;
};

}  // namespace rcsplat
