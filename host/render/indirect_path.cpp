// Path-traced indirect light: the same bounce the cache estimates, sampled per pixel in rounds with progress.
#include <algorithm>

#include "kernels/counter_random.h"
#include "passes/path_pass.h"
#include "render/indirect.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace {

// An RGB layer of the G-buffer's frame gathered into output pixels on the device, as every other layer (LayerPass):
// the sub-pixels' mean, times scale.
std::vector<float> gathered_rgb(IndirectFrame& f, const std::vector<float>& rgb, float scale) {
  std::vector<cl_float4> rgba(rgb.size() / 3);
  for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = cl_float4{{rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 0.0f}};
  const std::vector<float> mean = f.layers.mean_rgba(f.gpu.upload(rgba, CL_MEM_READ_ONLY, "path layers"));
  std::vector<float> out(f.layers.pixel_count() * 3);
  for (size_t i = 0; i < f.layers.pixel_count(); ++i)
    for (size_t c = 0; c < 3; ++c) out[3 * i + c] = mean[4 * i + c] * scale;
  return out;
}

}  // namespace

void path_traced_indirect(IndirectFrame& f) {
  const PathSettings& ps = f.settings.path;
  if (ps.samples == 0) throw Error("--spp must be at least 1");
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  double program_before = f.gpu.program_seconds();
  PathPass path(f.gpu, f.device_scene);
  st.program_s += f.gpu.program_seconds() - program_before;

  StageTimer timing(st.path_s);
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
    st.path_rays += path.rays_cast();
    means.push_back(path.mean_rgb());
    counts.push_back(samples);
    if (halves == 1) variance = path.mean_variance_rgb();
  }
  if (!f.progress) progress.finish();
  timing.stop();
  st.path_samples = ps.samples;
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
  img.indirect = gathered_rgb(f, indirect, 1.0f);
  // The output pixel's mean of independent sub-pixel estimates: the mean of their variances over the count.
  img.indirect_variance = gathered_rgb(f, variance, 1.0f / sub_pixels);
  for (size_t i = 0; i < img.color.size(); ++i) img.color[i] += img.indirect[i];
}

}  // namespace rcsplat
