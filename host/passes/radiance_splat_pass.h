// The radiance splat and its normalisation (kernels/radiance_splat.cl): owns the fixed-point sums, the resolved lobe
// radiance of the radiance-cached pixels, the lobe table on the device, and the G-buffer copy that placement of
// radiance records works on (only LOBE_HSH pixels see geometry in it).
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/brdf_table_pass.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class RadianceSplatPass {
 public:
  // table: the lobe table of the frame's order; table_row_of_material: its row for each scene material, -1 for
  // materials it does not hold.
  RadianceSplatPass(GpuContext& gpu, const BrdfTable& table, const std::vector<int>& table_row_of_material);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // The G-buffer with every pixel but the radiance-cached ones marked empty (placement's view of them).
  const GBufferView& radiance_cached_pixels(const GBufferView& gbuffer);

  // Clears and splats records 0 .. count - 1 (their coefficients of the table's order) at accuracy a; radiance_scale
  // bounds what a lobe can reflect. Blocks until done.
  void splat_all(const GBufferView& gbuffer, const cl::Buffer& records, const cl::Buffer& coefficients, uint32_t count,
                 float accuracy, float radiance_scale);
  void resolve(const GBufferView& gbuffer);
  // After resolve, with the records and coefficients of splat_all: radiance-cached pixels that no record reached take
  // the record that placement sat within `window` pixels of them (kernels/radiance_splat.cl); returns how many did.
  uint32_t fill_uncovered(const GBufferView& gbuffer, const cl::Buffer& records, const cl::Buffer& coefficients,
                          const cl::Buffer& record_at_pixel, int window);
  const cl::Buffer& lobe_radiance() const { return lobe_radiance_; }  // float4: L_o.rgb, sum w
  std::vector<float> lobe_radiance_rgbw();

 private:
  static constexpr const char* kProgram = "radiance_splat.cl";  // its kernels' file
  void size_for(const GBufferView& gbuffer);

  GpuContext& gpu_;
  NamedKernel keep_, clear_, splat_, resolve_, fill_;
  cl::Buffer table_, table_rows_, kept_samples_, sums_, lobe_radiance_, filled_;
  GBufferView kept_;
  RadianceSplatParams params_{};
  size_t pixels_ = 0;
};

}  // namespace rcsplat
