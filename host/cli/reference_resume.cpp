// Continuing a path-traced reference: the samples already in the file are kept and new ones, drawn with other seeds,
// are averaged in by count. The two halves' difference (indirect_variance) merges the same way, so the reference's
// own error stays known.
#include <string>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "image/image_io.h"
#include "render/camera.h"
#include "render/pixel_samples.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace {

unsigned parse_count(const std::string& path, const std::string& key, const std::string& value) {
  try {
    return unsigned(std::stoul(value));
  } catch (const std::exception&) {
    throw Error(path + ": attribute " + key + " is not a count: '" + value + "'");
  }
}

}  // namespace

bool resume_reference(GpuContext& gpu, const Scene& scene, const RenderOptions& o, const std::string& path,
                      RenderedImage& image) {
  ExrAttributes attributes = read_exr_attributes(path);
  auto need = [&](const std::string& key) {
    auto it = attributes.find(key);
    if (it == attributes.end()) throw Error(path + ": no " + key + " attribute: not a reference written by rcsplat");
    return it->second;
  };
  if (need("rcsplat:gi") != "path") throw Error(path + ": not a path-traced reference");
  if (need("rcsplat:scene") != scene.source)
    throw Error(path + ": rendered from " + need("rcsplat:scene") + ", not " + scene.source);
  if (need("rcsplat:stratified") != (o.settings.path.stratified ? "1" : "0"))
    throw Error(path + ": sampled " + (o.settings.path.stratified ? "without" : "with") + " stratification");
  // What this run renders must be what the file holds; a file from before an attribute existed holds its default.
  auto refuse_other = [&](const std::string& key, const std::string& absent, bool count, const std::string& now,
                          const std::string& option) {
    auto it = attributes.find(key);
    const std::string before =
        it == attributes.end() ? absent : count ? std::to_string(parse_count(path, key, it->second)) : it->second;
    if (before != now) throw Error(path + ": rendered with " + option + " " + before + ", not " + now);
  };
  // Bounces left to the scene (0) continue with the file's count.
  auto bounces_in_file = attributes.find("rcsplat:bounces");
  const unsigned file_bounces =
      bounces_in_file == attributes.end() ? 1u : parse_count(path, "rcsplat:bounces", bounces_in_file->second);
  if (o.settings.bounces) refuse_other("rcsplat:bounces", "1", true, std::to_string(o.settings.bounces), "--bounces");
  refuse_other("rcsplat:environment", "none", false, scene.environment.describe(), "environment");
  refuse_other("rcsplat:light_through_glass", "straight", false, light_through_glass_name(scene.glass_light),
               "--light-through-glass");
  // Pixel samples left to rcsplat (0) continue with the file's.
  auto pixel_samples_in_file = attributes.find("rcsplat:pixel_samples");
  const unsigned file_pixel_samples = pixel_samples_in_file == attributes.end()
                                          ? 1u
                                          : parse_count(path, "rcsplat:pixel_samples", pixel_samples_in_file->second);
  if (o.settings.pixel_samples)
    refuse_other("rcsplat:pixel_samples", "1", true, std::to_string(o.settings.pixel_samples), "--pixel-samples");
  refuse_other("rcsplat:pixel_points", "centres", false, pixel_points_name(o.settings), "pixel points");
  unsigned samples_before = parse_count(path, "rcsplat:path_samples", need("rcsplat:path_samples"));
  unsigned lights_before = parse_count(path, "rcsplat:light_samples", need("rcsplat:light_samples"));
  unsigned seed = parse_count(path, "rcsplat:seed", need("rcsplat:seed"));
  if (samples_before >= o.settings.path.samples) return false;
  int w = 0, h = 0;
  std::vector<float> indirect = read_exr_layer(path, "indirect", w, h);
  // Refused before any work: the frame this run would render must be the file's.
  int frame_w = o.settings.width, frame_h = o.settings.height;
  resolve_resolution(choose_camera(scene, o.settings.camera, o.settings.camera_overrides), frame_w, frame_h);
  if (frame_w != w || frame_h != h)
    throw Error(path + " is " + std::to_string(w) + "x" + std::to_string(h) + ", this frame " +
                std::to_string(frame_w) + "x" + std::to_string(frame_h));
  std::vector<float> variance = read_exr_layer(path, "indirect_variance", w, h);
  std::vector<float> direct = read_exr_layer(path, "direct", w, h);

  RenderSettings more = o.settings;
  more.bounces = file_bounces;
  more.pixel_samples = file_pixel_samples;
  more.path.samples = o.settings.path.samples - samples_before;
  more.seed = seed + samples_before;  // differs from every earlier part's seed: the parts are independent
  more.light_samples = o.settings.light_samples > lights_before ? o.settings.light_samples - lights_before : 0;
  log_info(path + ": has " + std::to_string(samples_before) + " samples per pixel; adding " +
           std::to_string(more.path.samples));
  image = render(gpu, scene, more);

  double n0 = samples_before, n1 = more.path.samples, n = n0 + n1;
  double l0 = lights_before, l1 = image.stats.primary.light_samples, l = std::max(l0 + l1, 1.0);
  for (size_t i = 0; i < indirect.size(); ++i) {
    image.indirect[i] = float((indirect[i] * n0 + image.indirect[i] * n1) / n);
    // Independent means: var((a n0 + b n1) / n) = (var a n0^2 + var b n1^2) / n^2.
    image.indirect_variance[i] = float((variance[i] * n0 * n0 + image.indirect_variance[i] * n1 * n1) / (n * n));
    image.direct[i] = float((direct[i] * l0 + image.direct[i] * l1) / l);
    image.color[i] = image.emission[i] + image.direct[i] + image.indirect[i];
  }
  image.stats.path.samples = unsigned(n);
  image.stats.primary.light_samples = unsigned(l0 + l1);
  return true;
}

Command add_reference_command(CLI::App& app, const HelpGroups& groups) {
  struct State {
    RenderOptions options;
    CameraFlags camera;
    EnvironmentFlags environment;
  };
  auto s = std::make_shared<State>();
  RenderSettings& settings = s->options.settings;
  settings.gi = GiMethod::path;
  settings.path.samples = kReferenceSamples;
  settings.path.stratified = true;
  settings.preferred_pixel_samples = kReferencePixelSamples;
  CLI::App* cmd =
      app.add_subcommand("reference", "Path-trace a converged reference (same materials, lights and bounce count)");
  add_frame_options(cmd, s->options, s->options.json_path, s->options.progress_lines, s->camera, s->environment,
                    groups);
  cmd->add_option("--spp", settings.path.samples,
                  "Samples per pixel (default " + std::to_string(kReferenceSamples) +
                      "); the light samples default to the same number");
  cmd->add_flag("--resume", s->options.resume, "Add samples to the .exr output an earlier run wrote, up to --spp in all");
  return {cmd, [s, cmd] {
            s->camera.apply(s->options.settings);
            s->environment.apply(s->options.environment);
            if (cmd->count("--light-samples") == 0) s->options.settings.light_samples = s->options.settings.path.samples;
            return run_render(s->options);
          }};
}

}  // namespace rcsplat
