// The image layers at output resolution (kernels/layers.cl): each output pixel gathers its side x side sub-pixels
// (--pixel-samples side^2; side 1 copies) on the device, so the host downloads and fills output-sized layers only.
// Owns the output-sized buffer the float4 images are gathered into.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "cache/cache_settings.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

class LayerPass {
 public:
  // A frame of out_width x out_height pixels whose G-buffer is side times as wide and high.
  LayerPass(GpuContext& gpu, unsigned side, int out_width, int out_height);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  unsigned side() const { return side_; }
  int out_width() const { return width_; }
  int out_height() const { return height_; }
  size_t pixel_count() const { return size_t(width_) * size_t(height_); }

  // A layer's pixels come down in pieces, each handed to `visit` (the first pixel's index, the piece, its pixels)
  // before the next is read: the whole layer at once would be fresh host memory (a 1080p frame's surface: 166 MB)
  // whose page faults cost more than the copy (benchmarks/RESULTS.md, "Issue 13, thirteenth step").
  template <typename T>
  using PieceVisit = std::function<void(size_t first, const T* piece, size_t count)>;

  // Emission, direct light (DirectPass's RGBA: A the shadow rays), albedo and normal averaged; position, depth and
  // triangle of the centre sub-pixel; shadow rays and the lobes' sub-pixels summed (PixelSurface).
  void surface(const GBufferView& gbuffer, const cl::Buffer& direct, const PieceVisit<PixelSurface>& visit);
  std::vector<PixelSurface> surface(const GBufferView& gbuffer, const cl::Buffer& direct);
  // Emission + direct light, the sub-pixels' means as surface() gives them, summed (RGBA, A 0): the colour before
  // indirect light of a frame that brings back nothing else (RenderSettings::color_only).
  void direct_colour(const GBufferView& gbuffer, const cl::Buffer& direct, const PieceVisit<float>& visit);
  // A visit that copies each piece's RGB (of RGBA, four floats a pixel) into `layer` (three floats a pixel, sized by
  // the caller), on all cores.
  static PieceVisit<float> rgb_into(std::vector<float>& layer);
  // A float4 image's sub-pixel mean (RGBA, four floats a pixel).
  void mean_rgba(const cl::Buffer& source, const PieceVisit<float>& visit);
  std::vector<float> mean_rgba(const cl::Buffer& source);
  // The cache's counts, four floats a pixel: the mean records reaching a sub-pixel (records_per_pixel), the records
  // sitting in the pixel (record_at_pixel >= 0), the sub-pixels with geometry whose irradiance weight (A) is 0, 0.
  void record_counts(const GBufferView& gbuffer, const cl::Buffer& irradiance, const cl::Buffer& records_per_pixel,
                     const cl::Buffer& record_at_pixel, const PieceVisit<float>& visit);
  std::vector<float> record_counts(const GBufferView& gbuffer, const cl::Buffer& irradiance,
                                   const cl::Buffer& records_per_pixel, const cl::Buffer& record_at_pixel);

  // Counts for the summary of a frame whose layers stay on the device (RenderSettings::color_only), summed on the
  // device from the sub-pixels as the host sums them from the layers, so both give the same numbers.
  // The sub-pixels with geometry of each lobe kind (LOBE_KINDS counts).
  std::array<uint64_t, LOBE_KINDS> count_lobes(const GBufferView& gbuffer);
  // The sum of a sub-pixel float4 image's A channel, whole numbers there (shadow rays, a pass's rays).
  uint64_t sum_alpha(const GBufferView& gbuffer, const cl::Buffer& source);
  // The sub-pixels with geometry no record reached (the irradiance's weight, A, is 0).
  uint64_t count_uncovered(const GBufferView& gbuffer, const cl::Buffer& irradiance);
  // The first record_count records whose reach sits at the lower and at the upper screen-space clamp, counted as the
  // host's count_clamped_radii counts them (render/placement.h): the records need not come back for the summary.
  std::array<uint64_t, 2> count_clamped_reaches(const cl::Buffer& records, uint32_t record_count,
                                                const CacheSettings& cache);

  // Pixels a piece holds (tests make it small, to cross pieces' edges); 0: kDefaultPiecePixels.
  // 20 MB of surface, 4 MB of RGBA: 16 blocks of parallel_ranges.
  static constexpr size_t kDefaultPiecePixels = size_t(1) << 18;
  void set_piece_pixels(size_t pixels) { piece_pixels_ = pixels ? pixels : kDefaultPiecePixels; }

 private:
  static constexpr const char* kProgram = "layers.cl";  // its kernels' file
  void resolve_rgba(const cl::Buffer& source, float scale);
  // Over the output frame's pixels, or its first `rows` rows (a band: the kernel offsets them).
  void launch(NamedKernel& kernel, int rows = -1);
  cl::Buffer& rgba_out();
  void check_frame(const GBufferView& gbuffer) const;
  // `buffer`'s pixels (per_pixel elements of T each) in pieces.
  template <typename T>
  void in_pieces(const cl::Buffer& buffer, size_t per_pixel, const PieceVisit<T>& visit);

  GpuContext& gpu_;
  unsigned side_;
  int width_, height_;
  // A count's sums over `items` work items (sub-pixels, records), read back (count_lobes, sum_alpha, count_uncovered,
  // count_clamped_reaches).
  template <typename Bind>
  std::vector<uint64_t> device_sums(NamedKernel& kernel, size_t items, size_t sums, const Bind& bind);
  template <typename Bind>
  std::vector<uint64_t> sub_pixel_sums(NamedKernel& kernel, const GBufferView& gbuffer, size_t sums, const Bind& bind);

  NamedKernel surface_, direct_colour_, rgba_, counts_, count_lobes_, sum_alpha_, count_uncovered_, count_clamped_;
  cl::Buffer sums_;  // device_sums' counters
  cl::Buffer rgba_out_;  // the float4 images' gathered pixels
  cl::Buffer surface_band_;  // one band of PixelSurfaces (surface())
  size_t surface_band_pixels_ = 0;
  size_t piece_pixels_ = kDefaultPiecePixels;
};

}  // namespace rcsplat
