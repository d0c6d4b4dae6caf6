// Path-traced indirect light: the same bounce the cache estimates, sampled per pixel in rounds with progress.
#include <algorithm>

#include "kernels/counter_random.h"
#include "passes/path_pass.h"
#include "render/indirect.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"

namespace rcsplat {
namespace {

// An RGB layer of the G-buffer's frame, already on the host, gathered into output pixels: the sub-pixels' mean, times
// scale. The same float operations in the same order as the device's gather of every other layer (kernels/layers.cl
// resolve_rgba), so the bits are those the device would give, without sending the layer back up to it.
std::vector<float> gathered_rgb(const LayerPass& layers, const std::vector<float>& rgb, float scale) {
  const size_t side = layers.side(), width = size_t(layers.out_width()), row = width * side;
  const float mean_scale = 1.0f / float(side * side);
  std::vector<float> out(layers.pixel_count() * 3);
  parallel_ranges(layers.pixel_count(), [&](size_t begin, size_t end) {
    for (size_t pixel = begin; pixel < end; ++pixel) {
      const size_t x = pixel % width, y = pixel / width, first = y * side * row + x * side;
      for (size_t c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (size_t j = 0; j < side; ++j)
          for (size_t i = 0; i < side; ++i) sum += rgb[3 * (first + j * row + i) + c];
        out[3 * pixel + c] = sum * mean_scale * scale;
      }
    }
  });
  return out;
}

}  // namespace

void path_traced_indirect(IndirectFrame& f) {
  const PathSettings& ps = f.settings.path;
  if (ps.samples == 0) throw Error("--spp must be at least 1");
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  StageTimer timing(st.path.seconds, f.gpu, st.program_s);
  PathPass& path = f.passes.path.get({}, [&] { return std::make_unique<PathPass>(f.gpu, f.device_scene); });
  // Two independent halves (different seeds): their difference estimates the error of their mean without bias, even
  // when stratified (the spread of stratified samples would overstate it). Plain sampling uses the samples' spread.
  unsigned halves = ps.stratified && ps.samples >= 2 ? 2 : 1;
  std::vector<std::vector<float>> means;
  std::vector<unsigned> counts;
  std::vector<float> variance;  // of each sub-pixel's mean
  Progress own_progress("path tracing", ps.samples);
  Progress& progress = f.progress ? *f.progress : own_progress;
  size_t done_before = f.progress ? f.progress_done_before : 0;
  for (unsigned h = 0; h < halves; ++h) {
    unsigned samples = halves == 1 ? ps.samples : (h == 0 ? ps.samples / 2 : ps.samples - ps.samples / 2);
    path.begin(f.gbuffer.view(), samples, ps.stratified, f.settings.seed + STREAM_ROUND_STEP * h, f.settings.bounces);
    // Rounds of about a second's work keep progress moving without costing launches.
    unsigned round = std::clamp(4000000u / unsigned(std::max<size_t>(f.gbuffer.view().pixel_count(), 1)), 1u, 64u);
    while (path.samples_done() < samples) {
      path.add_samples(round);
      progress.update(done_before + path.samples_done());
    }
    done_before += samples;
    st.path.rays += path.rays_cast();
    means.push_back(path.mean_rgb(halves == 1 ? &variance : nullptr));
    counts.push_back(samples);
  }
  if (!f.progress) progress.finish();
  timing.stop();
  st.path.samples = ps.samples;
  // Per sub-pixel (the G-buffer's frame), then gathered into output pixels.
  std::vector<float> indirect = means[0];
  if (halves == 2) {
    variance.resize(indirect.size());
    double w0 = double(counts[0]) / ps.samples, w1 = double(counts[1]) / ps.samples;
    for (size_t i = 0; i < indirect.size(); ++i) {
      double a = means[0][i], b = means[1][i];
      indirect[i] = float(w0 * a + w1 * b);
      // E[(a - b)^2] = var(a) + var(b); the mean's variance is w0^2 var(a) + w1^2 var(b), about a quarter of it.
      variance[i] = float((a - b) * (a - b) * (w0 * w0 + w1 * w1) / 2.0);
    }
  }
  const float sub_pixels = float(f.layers.side() * f.layers.side());
  img.indirect = gathered_rgb(f.layers, indirect, 1.0f);
  // The output pixel's mean of independent sub-pixel estimates: the mean of their variances over the count.
  img.indirect_variance = gathered_rgb(f.layers, variance, 1.0f / sub_pixels);
  for (size_t i = 0; i < img.color.size(); ++i) img.color[i] += img.indirect[i];
}

}  // namespace rcsplat
