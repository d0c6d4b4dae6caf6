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
  path.begin(f.gbuffer, ps.samples, ps.stratified, f.settings.seed);
  // Rounds of about a second's work keep progress moving without costing launches.
  unsigned round = std::clamp(4000000u / unsigned(std::max<size_t>(f.gbuffer.pixel_count(), 1)), 1u, 64u);
  Progress progress("path tracing", ps.samples);
  while (path.samples_done() < ps.samples) {
    path.add_samples(round);
    progress.update(path.samples_done());
  }
  progress.finish();
  st.path_s = seconds_since(t);
  st.path_samples = ps.samples;
  st.path_rays = path.rays_cast();
  img.indirect = path.mean_rgb();
  img.indirect_variance = path.mean_variance_rgb();
  for (size_t i = 0; i < img.color.size(); ++i) img.color[i] += img.indirect[i];
}

}  // namespace rcsplat
