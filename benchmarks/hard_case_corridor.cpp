// Issue 10's small bright indirect source, timed: the corridor of tests/cache_test_scenes.h (a 1e6 cd spot lights a
// disc of radius 0.25 m; everything else is lit only by that disc) at 256 x 192, against its exact indirect light
// (quadrature). Renders the cache with and without the light guide, and stratified path tracing given the guided
// cache's indirect time, three times each (median), and prints per-pixel and 8 x 8 block relMSE of the indirect
// layer. Writes the indirect layers as PNG at exposures -4, 0 and +2 into the output directory. With
// METAL_WALL_ROUGHNESS the walls and ceiling are metal of that roughness (radiance-cached at 0.45 .. 0.9), and the
// files are named corridor_metalROUGHNESS_*.
// SEED (default 7) renders another frame of the same scene.
//   build/benchmarks/hard_case_corridor OUT_DIR [GUIDE_RAYS [METAL_WALL_ROUGHNESS [SEED]]]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "corridor_scene.h"
#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "image/error_metrics.h"
#include "image/image_io.h"
#include "render/renderer.h"

using namespace rcsplat;

namespace {

double indirect_seconds(const RenderStats& s) {
  return s.guide.seconds + s.irradiance.records_s + s.irradiance.placement_s + s.irradiance.splat_s +
         s.irradiance.resolve_s + s.path.seconds + s.radiance.seconds() + s.glossy.seconds;
}

struct Run {
  RenderedImage image;
  double seconds;  // median of three
};

Run timed(GpuContext& gpu, const Scene& scene, const RenderSettings& settings) {
  std::vector<double> times;
  Run run;
  for (int i = 0; i < 3; ++i) {
    run.image = render(gpu, scene, settings);
    times.push_back(indirect_seconds(run.image.stats));
  }
  std::sort(times.begin(), times.end());
  run.seconds = times[1];
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : ".";
  GpuContext gpu(select_device(""));
  const float metal_roughness = argc > 3 ? std::stof(argv[3]) : 0.0f;
  const std::string prefix = metal_roughness > 0.0f ? "corridor_metal" + std::string(argv[3]) : "corridor";
  const Scene corridor = test::bright_patch_corridor(metal_roughness);
  RenderSettings settings;
  settings.width = 256;
  settings.height = 192;
  settings.light_samples = 1;
  settings.seed = argc > 4 ? unsigned(std::stoul(argv[4])) : 7u;
  if (argc > 2) settings.cache.guide_rays = unsigned(std::stoul(argv[2]));
  render(gpu, corridor, settings);  // compiles and caches the kernels
  Run guided = timed(gpu, corridor, settings);
  const std::vector<float> exact = test::corridor_indirect_by_quadrature(corridor, guided.image);
  RenderSettings unguided_settings = settings;
  unguided_settings.cache.guide_rays = 0;
  Run unguided = timed(gpu, corridor, unguided_settings);
  RenderSettings path_settings = settings;
  path_settings.gi = GiMethod::path;
  path_settings.path.stratified = true;
  path_settings.path.samples = 16;
  const double per_sample = timed(gpu, corridor, path_settings).seconds / 16.0;
  unsigned side = std::max(1u, unsigned(std::ceil(std::sqrt(guided.seconds / per_sample))));  // at least equal time
  path_settings.path.samples = side * side;
  Run path = timed(gpu, corridor, path_settings);

  std::printf("device %s, %s 256x192, indirect layer against the quadrature\n", gpu.device_info().name.c_str(),
              prefix.c_str());
  std::printf("%-34s %10s %14s %14s\n", "method", "seconds", "relMSE", "8x8 relMSE");
  auto row = [&](const char* name, const Run& r, const char* file) {
    std::printf("%-34s %10.3f %14.4e %14.4e\n", name, r.seconds, image_error(r.image.indirect, exact).rel_mse,
                block_rel_mse(r.image.indirect, exact, settings.width, settings.height, 8));
    for (int stops : {-4, 0, 2})
      write_png(out + "/" + file + "_ev" + std::to_string(stops) + ".png", settings.width, settings.height,
                r.image.indirect, float(stops));
  };
  std::string guided_name = "cache, light guide, " + std::to_string(settings.cache.guide_rays) + " rays";
  row(guided_name.c_str(), guided, (prefix + "_guided").c_str());
  row("cache, --guide-rays 0", unguided, (prefix + "_unguided").c_str());
  char name[64];
  std::snprintf(name, sizeof name, "stratified path, %u spp", path_settings.path.samples);
  row(name, path, (prefix + "_path").c_str());
  for (int stops : {-4, 0, 2})
    write_png(out + "/" + prefix + "_exact_ev" + std::to_string(stops) + ".png", settings.width, settings.height, exact,
              float(stops));
  return 0;
}
