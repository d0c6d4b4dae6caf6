#include "passes/layer_pass.h"

#include <algorithm>
#include <string>

#include "util/error.h"

namespace rcsplat {

LayerPass::LayerPass(GpuContext& gpu, unsigned side, int out_width, int out_height)
    : gpu_(gpu),
      side_(std::max(1u, side)),
      width_(out_width),
      height_(out_height),
      surface_(gpu.kernel("layers.cl", "resolve_surface")),
      rgba_(gpu.kernel("layers.cl", "resolve_rgba")),
      counts_(gpu.kernel("layers.cl", "resolve_record_counts")) {}

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

void LayerPass::launch(NamedKernel& kernel) {
  // Every kernel of layers.cl takes the sub-pixel grid's side and the output frame, and runs over its pixels.
  kernel.set("side", cl_uint(side_)).set("out_width", cl_int(width_)).set("out_height", cl_int(height_));
  kernel.launch_2d(size_t(width_), size_t(height_), gpu_.groups().tile_side);
}

std::vector<PixelSurface> LayerPass::surface(const GBufferView& gbuffer, const cl::Buffer& direct) {
  check_frame(gbuffer);
  // Freed on return: it would otherwise sit through the frame's peak (records, photon map).
  const cl::Buffer out =
      gpu_.buffer(CL_MEM_WRITE_ONLY, std::max<size_t>(pixel_count(), 1) * sizeof(PixelSurface), "image layers");
  surface_.set_buffer<GBufferSample>("gbuffer", gbuffer.samples)
      .set_buffer<cl_float4>("direct", direct)
      .set_buffer<PixelSurface>("out", out);
  launch(surface_);
  return gpu_.download<PixelSurface>(out, pixel_count());
}

std::vector<float> LayerPass::resolve_rgba(const cl::Buffer& source, float scale) {
  rgba_.set_buffer<cl_float4>("source", source)
      .set("scale", cl_float(scale))
      .set_buffer<cl_float4>("out", rgba_out());
  launch(rgba_);
  return gpu_.download<float>(rgba_out_, pixel_count() * 4);
}

std::vector<float> LayerPass::mean_rgba(const cl::Buffer& source) {
  return resolve_rgba(source, 1.0f / float(side_ * side_));
}

std::vector<float> LayerPass::sum_rgba(const cl::Buffer& source) { return resolve_rgba(source, 1.0f); }

std::vector<float> LayerPass::record_counts(const GBufferView& gbuffer, const cl::Buffer& irradiance,
                                            const cl::Buffer& records_per_pixel, const cl::Buffer& record_at_pixel) {
  check_frame(gbuffer);
  counts_.set_buffer<GBufferSample>("gbuffer", gbuffer.samples)
      .set_buffer<cl_float4>("irradiance", irradiance)
      .set_buffer<cl_uint>("records_per_pixel", records_per_pixel)
      .set_buffer<cl_int>("record_at_pixel", record_at_pixel)
      .set_buffer<cl_float4>("out", rgba_out());
  launch(counts_);
  return gpu_.download<float>(rgba_out_, pixel_count() * 4);
}

}  // namespace rcsplat
