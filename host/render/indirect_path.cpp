// Path-traced indirect light: the same bounce the cache estimates, sampled per pixel in rounds with progress.
#include <algorithm>

#include "passes/path_pass.h"
#include "render/indirect.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {

void path_traced_indirect(IndirectFrame& f) {
  const PathSettings& ps = f.settings.path;
  if (ps.samples == 0) throw Error("--spp must be at least 1");
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  double program_before = f.gpu.program_seconds();
  PathPass path(f.gpu, f.device_scene);
  st.program_s += f.gpu.program_seconds() - program_before;

  auto t = Clock::now();
  // Two independent halves (different seeds): their difference estimates the error of their mean without bias, even
  // when stratified (the spread of stratified samples would overstate it). Plain sampling uses the samples' spread.
  unsigned halves = ps.stratified && ps.samples >= 2 ? 2 : 1;
  std::vector<std::vector<float>> means;
  std::vector<unsigned> counts;
  Progress own_progress("path tracing", ps.samples);
  Progress& progress = f.progress ? *f.progress : own_progress;
  size_t done_before = f.progress ? f.progress_done_before : 0;
  for (unsigned h = 0; h < halves; ++h) {
    unsigned samples = halves == 1 ? ps.samples : (h == 0 ? ps.samples / 2 : ps.samples - ps.samples / 2);
    path.begin(f.gbuffer.view(), samples, ps.stratified, f.settings.seed + 0x9e3779b9u * h, f.settings.bounces);
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
    if (halves == 1) img.indirect_variance = path.mean_variance_rgb();
  }
  if (!f.progress) progress.finish();
  st.path_s = seconds_since(t);
  st.path_samples = ps.samples;
  img.indirect = means[0];
  if (halves == 2) {
    img.indirect_variance.resize(img.indirect.size());
    double w0 = double(counts[0]) / ps.samples, w1 = double(counts[1]) / ps.samples;
    for (size_t i = 0; i < img.indirect.size(); ++i) {
      double a = means[0][i], b = means[1][i];
      img.indirect[i] = float(w0 * a + w1 * b);
      // E[(a - b)^2] = var(a) + var(b); the mean's variance is w0^2 var(a) + w1^2 var(b), about a quarter of it.
      img.indirect_variance[i] = float((a - b) * (a - b) * (w0 * w0 + w1 * w1) / 2.0);
    }
  }
  for (size_t i = 0; i < img.color.size(); ++i) img.color[i] += img.indirect[i];
}

}  // namespace rcsplat
