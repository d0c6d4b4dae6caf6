#include "passes/layer_pass.h"

#include <algorithm>
#include <string>

#include "util/error.h"
#include "util/parallel.h"

namespace rcsplat {
void LayerPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }

LayerPass::LayerPass(GpuContext& gpu, unsigned side, int out_width, int out_height)
    : gpu_(gpu),
      side_(std::max(1u, side)),
      width_(out_width),
      height_(out_height),
      surface_(gpu.kernel(kProgram, "resolve_surface")),
      direct_colour_(gpu.kernel(kProgram, "resolve_direct_colour")),
      rgba_(gpu.kernel(kProgram, "resolve_rgba")),
      counts_(gpu.kernel(kProgram, "resolve_record_counts")),
      count_lobes_(gpu.kernel(kProgram, "count_lobes")),
      sum_alpha_(gpu.kernel(kProgram, "sum_alpha")),
      count_uncovered_(gpu.kernel(kProgram, "count_uncovered")),
      count_clamped_(gpu.kernel(kProgram, "count_clamped_reaches")) {}

cl::Buffer& LayerPass::rgba_out() {
  // Made on first use, at the frame's end: the passes' own buffers peak before it.
  if (!rgba_out_()) rgba_out_ = gpu_.buffer(CL_MEM_WRITE_ONLY, std::max<size_t>(pixel_count(), 1) * 4 * sizeof(float),
                                            "image layers");
  return rgba_out_;
}

void LayerPass::check_frame(const GBufferView& gbuffer) const {
  // A mismatch is a bug in the caller, never the user's input: say so rather than read past a buffer.
  if (gbuffer.width != width_ * int(side_) || gbuffer.height != height_ * int(side_))
    throw Error("internal: a " + std::to_string(gbuffer.width) + "x" + std::to_string(gbuffer.height) +
                " G-buffer is not " + std::to_string(side_) + " times the " + std::to_string(width_) + "x" +
                std::to_string(height_) + " image");
}

void LayerPass::launch(NamedKernel& kernel, int rows) {
  // Every kernel of layers.cl takes the sub-pixel grid's side and the output frame, and runs over its pixels.
  kernel.set("side", cl_uint(side_)).set("out_width", cl_int(width_)).set("out_height", cl_int(height_));
  kernel.launch_2d(size_t(width_), size_t(rows < 0 ? height_ : rows), gpu_.groups().tile_side);
}

template <typename T>
void LayerPass::in_pieces(const cl::Buffer& buffer, size_t per_pixel, const PieceVisit<T>& visit) {
  std::vector<T> piece(std::min(pixel_count(), piece_pixels_) * per_pixel);
  for (size_t first = 0; first < pixel_count(); first += piece_pixels_) {
    const size_t count = std::min(piece_pixels_, pixel_count() - first);
    gpu_.queue().enqueueReadBuffer(buffer, CL_TRUE, first * per_pixel * sizeof(T), count * per_pixel * sizeof(T),
                                   piece.data());
    visit(first, piece.data(), count);
  }
}

namespace {

// A visit that copies each piece into `out`, per_pixel elements a pixel: the whole layer, for callers that want it.
template <typename T>
LayerPass::PieceVisit<T> into(std::vector<T>& out, size_t per_pixel) {
  return [&out, per_pixel](size_t first, const T* piece, size_t count) {
    std::copy(piece, piece + count * per_pixel, out.begin() + std::ptrdiff_t(first * per_pixel));
  };
}

}  // namespace

void LayerPass::surface(const GBufferView& gbuffer, const cl::Buffer& direct, const PieceVisit<PixelSurface>& visit) {
  check_frame(gbuffer);
  // Bands of whole rows, about a piece each: the buffer holds one band, made once and kept, so neither a frame's peak
  // nor a later frame pays for a whole frame of surfaces (a 1024 x 768 frame's: 60 MiB).
  const int band_rows =
      int(std::clamp<size_t>(piece_pixels_ / size_t(std::max(width_, 1)), 1, size_t(std::max(height_, 1))));
  const size_t band_pixels = size_t(band_rows) * size_t(width_);
  if (!surface_band_() || surface_band_pixels_ < band_pixels) {
    surface_band_ = cl::Buffer();  // freed before its successor is made
    surface_band_ = gpu_.buffer(CL_MEM_WRITE_ONLY, std::max<size_t>(band_pixels, 1) * sizeof(PixelSurface),
                                "image layers");
    surface_band_pixels_ = band_pixels;
  }
  std::vector<PixelSurface> piece(band_pixels);
  for (int first_row = 0; first_row < height_; first_row += band_rows) {
    const int rows = std::min(band_rows, height_ - first_row);
    const size_t count = size_t(rows) * size_t(width_);
    surface_.set_buffer<GBufferSample>("gbuffer", gbuffer.samples)
        .set_buffer<cl_float4>("direct", direct)
        .set_buffer<PixelSurface>("out", surface_band_)
        .set("first_row", cl_int(first_row))
        .set("rows", cl_int(rows));
    launch(surface_, rows);
    gpu_.queue().enqueueReadBuffer(surface_band_, CL_TRUE, 0, count * sizeof(PixelSurface), piece.data());
    visit(size_t(first_row) * size_t(width_), piece.data(), count);
  }
}

std::vector<PixelSurface> LayerPass::surface(const GBufferView& gbuffer, const cl::Buffer& direct) {
  std::vector<PixelSurface> out(pixel_count());
  surface(gbuffer, direct, into(out, 1));
  return out;
}

LayerPass::PieceVisit<float> LayerPass::rgb_into(std::vector<float>& layer) {
  return [&layer](size_t first, const float* piece, size_t count) {
    parallel_ranges(count, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k)
        for (size_t c = 0; c < 3; ++c) layer[3 * (first + k) + c] = piece[4 * k + c];
    });
  };
}

void LayerPass::direct_colour(const GBufferView& gbuffer, const cl::Buffer& direct, const PieceVisit<float>& visit) {
  check_frame(gbuffer);
  direct_colour_.set_buffer<GBufferSample>("gbuffer", gbuffer.samples)
      .set_buffer<cl_float4>("direct", direct)
      .set_buffer<cl_float4>("out", rgba_out());
  launch(direct_colour_);
  in_pieces<float>(rgba_out_, 4, visit);
}

void LayerPass::resolve_rgba(const cl::Buffer& source, float scale) {
  rgba_.set_buffer<cl_float4>("source", source)
      .set("scale", cl_float(scale))
      .set_buffer<cl_float4>("out", rgba_out());
  launch(rgba_);
}

void LayerPass::mean_rgba(const cl::Buffer& source, const PieceVisit<float>& visit) {
  resolve_rgba(source, 1.0f / float(side_ * side_));
  in_pieces<float>(rgba_out_, 4, visit);
}

std::vector<float> LayerPass::mean_rgba(const cl::Buffer& source) {
  std::vector<float> out(pixel_count() * 4);
  mean_rgba(source, into(out, 4));
  return out;
}

void LayerPass::record_counts(const GBufferView& gbuffer, const cl::Buffer& irradiance,
                              const cl::Buffer& records_per_pixel, const cl::Buffer& record_at_pixel,
                              const PieceVisit<float>& visit) {
  check_frame(gbuffer);
  counts_.set_buffer<GBufferSample>("gbuffer", gbuffer.samples)
      .set_buffer<cl_float4>("irradiance", irradiance)
      .set_buffer<cl_uint>("records_per_pixel", records_per_pixel)
      .set_buffer<cl_int>("record_at_pixel", record_at_pixel)
      .set_buffer<cl_float4>("out", rgba_out());
  launch(counts_);
  in_pieces<float>(rgba_out_, 4, visit);
}

std::vector<float> LayerPass::record_counts(const GBufferView& gbuffer, const cl::Buffer& irradiance,
                                            const cl::Buffer& records_per_pixel, const cl::Buffer& record_at_pixel) {
  std::vector<float> out(pixel_count() * 4);
  record_counts(gbuffer, irradiance, records_per_pixel, record_at_pixel, into(out, 4));
  return out;
}

template <typename Bind>
std::vector<uint64_t> LayerPass::device_sums(NamedKernel& kernel, size_t items, size_t sums, const Bind& bind) {
  static_assert(LOBE_KINDS >= 2, "sums_ holds LOBE_KINDS counters");
  if (!sums_()) sums_ = gpu_.buffer(CL_MEM_READ_WRITE, LOBE_KINDS * sizeof(cl_ulong), "image layers");
  gpu_.queue().enqueueFillBuffer(sums_, cl_ulong(0), 0, sums * sizeof(cl_ulong));
  bind(kernel);
  kernel.set_buffer<cl_ulong>("sums", sums_);
  kernel.launch(items, LAYER_COUNT_GROUP);
  const std::vector<cl_ulong> read = gpu_.download<cl_ulong>(sums_, sums);
  return std::vector<uint64_t>(read.begin(), read.end());
}

template <typename Bind>
std::vector<uint64_t> LayerPass::sub_pixel_sums(NamedKernel& kernel, const GBufferView& gbuffer, size_t sums,
                                                const Bind& bind) {
  check_frame(gbuffer);
  const size_t sub_pixels = gbuffer.pixel_count();
  return device_sums(kernel, sub_pixels, sums, [&](NamedKernel& k) {
    bind(k);
    k.set("sub_pixels", cl_uint(sub_pixels));
  });
}

std::array<uint64_t, LOBE_KINDS> LayerPass::count_lobes(const GBufferView& gbuffer) {
  const std::vector<uint64_t> sums = sub_pixel_sums(count_lobes_, gbuffer, LOBE_KINDS, [&](NamedKernel& k) {
    k.set_buffer<GBufferSample>("gbuffer", gbuffer.samples);
  });
  std::array<uint64_t, LOBE_KINDS> counts{};
  std::copy(sums.begin(), sums.end(), counts.begin());
  return counts;
}

uint64_t LayerPass::sum_alpha(const GBufferView& gbuffer, const cl::Buffer& source) {
  return sub_pixel_sums(sum_alpha_, gbuffer, 1, [&](NamedKernel& k) { k.set_buffer<cl_float4>("source", source); })[0];
}

uint64_t LayerPass::count_uncovered(const GBufferView& gbuffer, const cl::Buffer& irradiance) {
  return sub_pixel_sums(count_uncovered_, gbuffer, 1, [&](NamedKernel& k) {
    k.set_buffer<GBufferSample>("gbuffer", gbuffer.samples).set_buffer<cl_float4>("irradiance", irradiance);
  })[0];
}

std::array<uint64_t, 2> LayerPass::count_clamped_reaches(const cl::Buffer& records, uint32_t record_count,
                                                        const CacheSettings& cache) {
  if (record_count == 0) return {0, 0};
  const std::vector<uint64_t> sums = device_sums(count_clamped_, record_count, 2, [&](NamedKernel& k) {
    k.set_buffer<CacheRecord>("records", records)
        .set("record_count", cl_uint(record_count))
        .set("accuracy", cl_float(cache.accuracy))
        .set("min_reach_pixels", cl_float(cache.min_reach_pixels))
        .set("max_reach_pixels", cl_float(cache.max_reach_pixels));
  });
  return {sums[0], sums[1]};
}

}  // namespace rcsplat
