// Issue 41 item 4's case, measured: the room lit through a gap (tests/gap_room_scene.h) at 320 x 240, rendered with
// the render defaults (bounces and their method chosen from the scene: the photon map), with the same records taking
// their later bounces by path continuation (--bounce-method path), and with one bounce, against stratified path
// tracing with the defaults' bounce count (REFERENCE_SPP samples a pixel, default 1024). Prints each image's mean
// against the reference's and its per-pixel and 8 x 8 block relMSE (the whole image a user sees), and writes every
// image as PNG at exposures -2, 0 and +2 into OUT_DIR. PHOTON_PATHS (0: the default rounds) shoots the photon map
// as one round of that many paths (--photons).
// MIN_SUPPORTS (default 0): --photon-min-support values to render beside the default's, comma-separated. SEEDS
// (default 1): each render made with seeds 1..SEEDS, its numbers averaged (a cache's error is blotches: one seed's
// mean moves by about 1% here); the PNGs are the last seed's.
//   build/benchmarks/gap_room OUT_DIR [REFERENCE_SPP [GAP_HEIGHT [PHOTON_PATHS [MIN_SUPPORTS [SEEDS]]]]]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "gap_room_scene.h"
#include "image/error_metrics.h"
#include "image/image_io.h"
#include "render/renderer.h"

using namespace rcsplat;

namespace {

double mean(const std::vector<float>& image) {
  double sum = 0.0;
  for (float v : image) sum += v;
  return image.empty() ? 0.0 : sum / double(image.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : ".";
  const unsigned reference_spp = argc > 2 ? unsigned(std::stoul(argv[2])) : 1024u;
  const float gap = argc > 3 ? std::stof(argv[3]) : 0.3f;
  const unsigned photon_paths = argc > 4 ? unsigned(std::stoul(argv[4])) : 0u;
  const unsigned seeds = argc > 6 ? unsigned(std::stoul(argv[6])) : 1u;
  std::vector<float> min_supports;  // besides the default's
  for (std::string list = argc > 5 ? argv[5] : "0"; !list.empty();) {
    size_t comma = list.find(',');
    min_supports.push_back(std::stof(list.substr(0, comma)));
    list = comma == std::string::npos ? "" : list.substr(comma + 1);
  }
  GpuContext gpu(select_device(""));
  const Scene room = test::gap_lit_room(gap);
  Renderer renderer(gpu, room);
  RenderSettings defaults;  // bounces, their method and pixel samples chosen, as the command line does
  defaults.width = 320;
  defaults.height = 240;
  defaults.photon_paths = photon_paths;
  const FramePlan plan = renderer.plan(defaults);

  struct Run {
    std::string name, file;
    RenderSettings settings;
    RenderedImage image;
  };
  std::vector<Run> runs;
  runs.push_back({"render defaults (" + std::to_string(plan.settings.bounces) + " bounces, " +
                      bounce_method_name(plan.settings.bounce_method) + ")",
                  "gap_default", defaults, {}});
  for (float support : min_supports) {
    RenderSettings other = defaults;
    other.photon_min_support = support;
    runs.push_back({"photons, --photon-min-support " + std::to_string(int(support)),
                    "gap_min_support_" + std::to_string(int(support)), other, {}});
  }
  RenderSettings path_bounces = defaults;
  path_bounces.bounces = plan.settings.bounces;
  path_bounces.bounce_method = BounceMethod::path;
  runs.push_back({"--bounce-method path", "gap_path_bounces", path_bounces, {}});
  RenderSettings one = defaults;
  one.bounces = 1;
  runs.push_back({"one bounce", "gap_one_bounce", one, {}});
  RenderSettings reference = defaults;
  reference.gi = GiMethod::path;
  reference.path.stratified = true;
  reference.path.samples = reference_spp;
  reference.bounces = plan.settings.bounces;
  reference.bounce_method = BounceMethod::path;
  const RenderedImage truth = renderer.render(reference);

  std::printf("device %s, %s (gap %.2f m) 320x240, the full image against stratified path tracing at %u spp and "
              "%u bounces (mean %.5f)\n",
              gpu.device_info().name.c_str(), room.source.c_str(), double(gap), reference_spp,
              plan.settings.bounces, mean(truth.color));
  std::printf("%u seed%s: means over seeds 1..%u, and of the means their spread (standard deviation)\n", seeds,
              seeds > 1 ? "s" : "", seeds);
  std::printf("%-36s %9s %10s %8s %12s %12s\n", "render", "seconds", "mean/ref", "spread", "relMSE", "8x8 relMSE");
  for (Run& run : runs) {
    double seconds = 0.0, ratio = 0.0, ratio2 = 0.0, rel_mse = 0.0, block = 0.0;
    for (unsigned seed = 1; seed <= seeds; ++seed) {
      run.settings.seed = seed;
      run.image = renderer.render(run.settings);
      const double r = mean(run.image.color) / mean(truth.color);
      seconds += run.image.stats.seconds_without_builds() / seeds;
      ratio += r / seeds;
      ratio2 += r * r / seeds;
      rel_mse += image_error(run.image.color, truth.color).rel_mse / seeds;
      block += block_rel_mse(run.image.color, truth.color, truth.width, truth.height, 8) / seeds;
    }
    std::printf("%-36s %9.3f %10.4f %8.4f %12.4e %12.4e\n", run.name.c_str(), seconds, ratio,
                std::sqrt(std::max(ratio2 - ratio * ratio, 0.0)), rel_mse, block);
  }
  runs.push_back({"reference", "gap_reference", reference, truth});
  for (const Run& run : runs)
    for (int stops : {-2, 0, 2})
      write_png(out + "/" + run.file + "_ev" + std::to_string(stops) + ".png", run.image.width, run.image.height,
                run.image.color, float(stops));
  return 0;
}
