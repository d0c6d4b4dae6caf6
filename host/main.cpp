// rcsplat: global illumination by radiance cache splatting on OpenCL devices. Command-line entry point.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <new>

#include "cl/gpu_context.h"
#include "cli/commands.h"
#include "kernels/hsh.h"
#include "render/pixel_samples.h"
#include "util/error.h"
#include "util/host_heap.h"
#include "util/log.h"

namespace {

using namespace rcsplat;

std::string shortest(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(v));
  return text;
}

std::optional<glm::vec3> as_vec3(const std::vector<float>& v) {
  if (v.empty()) return std::nullopt;
  return glm::vec3(v[0], v[1], v[2]);
}

struct CameraFlags {
  std::vector<float> eye, target, up;
  std::optional<float> fov;
  void apply(RenderSettings& s) const {
    s.camera_overrides.eye = as_vec3(eye);
    s.camera_overrides.target = as_vec3(target);
    s.camera_overrides.up = as_vec3(up);
    s.camera_overrides.fov_degrees = fov;
  }
};

// Light from outside the scene (scene/environment.h), for render, reference and info.
struct EnvironmentFlags {
  std::vector<float> sky;
  void add(CLI::App* cmd, EnvironmentSettings& e) {
    cmd->add_option("--sky", sky, "Uniform sky radiance R,G,B seen by every ray that leaves the scene")
        ->delimiter(',')
        ->expected(3);
    cmd->add_option("--environment", e.file,
                    "Equirectangular environment map (.exr, .hdr): +Y up, its centre column toward -Z; its bright "
                    "peak (a sun) is importance-sampled by shadow rays, the rest gathered with the indirect light");
    cmd->add_option("--environment-intensity", e.intensity, "Multiplies the environment map (default 1)");
    cmd->add_option("--environment-rotation", e.rotation_degrees,
                    "Rotates the environment map about +Y by this many degrees (default 0)");
  }
  void apply(EnvironmentSettings& e) const { e.sky = as_vec3(sky); }
};

// What a scene may make rcsplat read and hold (scene/scene_limits.h, docs/SECURITY.md): for every command that loads
// one. --max-device-memory only where a frame is rendered.
void add_scene_limit_options(CLI::App* cmd, SceneLimits& limits, bool device) {
  cmd->add_option("--asset-root", limits.asset_roots,
                  "Also let the scene read files inside this folder (through '..' or symbolic links); for a scene you "
                  "trust (default: only the scene's own folder and the folders under it)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--max-triangles", limits.max_triangles,
                  "Refuse a scene that places more triangles, instances counted (default 16777216)")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32));
  cmd->add_option_function<double>(
         "--max-host-memory", [&limits](double gib) { limits.host_memory_bytes = uint64_t(gib * double(1ull << 30)); },
         "GiB of host memory the scene may take: files read, textures decoded, triangles (default: 3/4 of this "
         "machine's memory)")
      ->check(CLI::Range(1.0 / 1024.0, 65536.0));
  if (device)
    cmd->add_option_function<double>(
           "--max-device-memory",
           [&limits](double gib) { limits.device_memory_bytes = uint64_t(gib * double(1ull << 30)); },
           "GiB of device memory a frame may hold at once (default: all the device has)")
        ->check(CLI::Range(1.0 / 1024.0, 65536.0));
}

// The options every image-making command shares: scene, outputs, device, frame and camera, light samples.
void add_frame_options(CLI::App* cmd, RenderOptions& o, CameraFlags& cam, EnvironmentFlags& env,
                       const std::string& lab) {
  cmd->add_option("scene", o.scene_path, "glTF 2.0 scene (.gltf or .glb); default: the built-in Cornell box");
  cmd->add_option("-o,--output", o.outputs, "Output image(s): .exr (linear, with layers) or .png (tone-mapped)")
      ->required();
  cmd->add_option("--device", o.device, "OpenCL device: index or name substring (see `rcsplat devices`)");
  // The library's 0 (the camera's aspect decides) is not for the command line, which leaves the option out instead.
  cmd->add_option("--width", o.settings.width, "Image width in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", o.settings.height, "Image height in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--camera", o.settings.camera, "Index of the scene camera to use")->check(CLI::NonNegativeNumber);
  cmd->add_option("--eye", cam.eye, "Camera position x,y,z")->delimiter(',')->expected(3);
  cmd->add_option("--target", cam.target, "Point the camera looks at x,y,z")->delimiter(',')->expected(3);
  cmd->add_option("--up", cam.up, "Camera up vector x,y,z")->delimiter(',')->expected(3);
  cmd->add_option("--fov", cam.fov, "Vertical field of view in degrees");
  cmd->add_option("--light-samples", o.settings.light_samples,
                  "Samples per pixel on emissive triangles (rounded up to a square; 0 to 1048576)");
  cmd->add_option("--seed", o.settings.seed, "Seed of the sample pattern");
  cmd->add_option("--pixel-samples", o.settings.pixel_samples,
                  "Primary samples per pixel, a square number (4: a 2x2 sub-pixel grid) for anti-aliased edges; light "
                  "and path samples are per pixel, records are those of one sample; default 4 for render, 16 for "
                  "reference (a finer grid, so compare counts a render's edge aliasing as error), fewer where --spp "
                  "does not divide by them or the frame is very large; path tracing takes each sample at a random "
                  "point of its cell of the grid, so it integrates over the pixel's area");
  cmd->add_flag("!--sub-pixel-grid", o.settings.path.pixel_area,
                "Path tracing: take the pixel samples at the fixed points a cache render shades (a rotated grid, one "
                "point in each cell of the s x s grid) instead of a random point of each cell")
      ->group(lab);
  cmd->add_option("--bounces", o.settings.bounces,
                  "Indirect bounces: 1 lights the first bounce's hit directly, each more adds a reflection (every "
                  "method, the reference too); default 0: chosen from the scene, the fewest that leave out at most 5% "
                  "of the indirect light, as a few photons measure it (at most 8; 3 with --sky or --environment); at most " +
                      std::to_string(kMaxBounces));
  env.add(cmd, o.environment);
  add_scene_limit_options(cmd, o.limits, true);
  cmd->add_option("--exposure", o.exposure, "PNG exposure in stops");
  cmd->add_option("--json", o.json_path, "Also write the summary as JSON");
}

// How `render` and `animate` compute a frame: the quality preset, the indirect-light method and the cache's options.
struct RenderMethodFlags {
  std::string gi = "splat", hemisphere, spacing, fine_hemisphere, bounce_method;
  bool glossy_paths = false, glossy_uniform = false, light_uniform = false;

  void add(CLI::App* cmd, RenderOptions& o, const std::string& lab) {
    cmd->add_option("--cache-in", o.cache_in,
                    "Splat: start from the irradiance records of a cache file that --cache-out wrote for this scene "
                    "and these settings")
        ->check(CLI::ExistingFile);
    cmd->add_option("--cache-out", o.cache_out,
                    "Splat: write the irradiance records kept after the last frame to this cache file");
    cmd->add_option("--quality", o.quality,
                    "Quality preset: draft (a quick look: accuracy 0.6, 8x16 rays a record, one sample a pixel, 4 "
                    "light samples), standard (the defaults), final (accuracy 0.15, a 4x4 grid of pixel samples "
                    "where the frame allows, 64 light samples); options given on the command line win")
        ->check(CLI::IsMember({"draft", "standard", "final"}));
    cmd->add_option("--gi", gi,
                    "Indirect light: splat (radiance cache splatting, default), octree (classic "
                    "irradiance cache on the host), path (path tracing), none")
        ->check(CLI::IsMember({"splat", "octree", "path", "none"}));
    const CacheSettings cache_defaults;
    cmd->add_option("--accuracy", o.settings.cache.accuracy,
                    "Cache accuracy a: records reach where Ward's weight exceeds 1/a; smaller is finer (" +
                        shortest(kMinAccuracy) + " to " + shortest(kMaxAccuracy) + ", default " +
                        shortest(cache_defaults.accuracy) + ")");
    cmd->add_option("--hemisphere", hemisphere,
                    "Rays per record as MxN strata (theta x phi), default " +
                        std::to_string(cache_defaults.theta_strata) + "x" + std::to_string(cache_defaults.phi_strata));
    cmd->add_option("--fine-hemisphere", fine_hemisphere,
                    "Rays per record for the records placed at the finest level (spacing 1), which reach only a "
                    "few pixels each, as MxN; default: as --hemisphere")
        ->group(lab);
    cmd->add_option("--spacing", spacing,
                    "Record spacing MIN,MAX in pixels: a record's reach a*R is clamped to it; default " +
                        shortest(cache_defaults.min_reach_pixels) + "," + shortest(cache_defaults.max_reach_pixels))
        ->group(lab);
    cmd->add_option("--placement-lines", o.settings.cache.placement_lines,
                    "Record spacings and reaches (--spacing) hold for an image this many lines high; a taller one "
                    "scales them, so that records follow the scene rather than the image; 0: never scale; default " +
                        std::to_string(cache_defaults.placement_lines))
        ->group(lab);
    cmd->add_option("--hessian-error", o.settings.cache.hessian_error,
                    "Record radii from the occlusion Hessian of the irradiance with this error budget (Schwarzhaupt "
                    "et al. 2012); 0: Ward's split sphere (harmonic mean hit distance); default " +
                        shortest(cache_defaults.hessian_error))
        ->group(lab);
    cmd->add_option("--adaptive-rays", o.settings.cache.adaptive_error,
                    "Adaptive rays: trace each record with half the strata each way first, and again with all "
                    "MxN where its estimated relative error is above this; 0: all MxN at once; default " +
                        shortest(cache_defaults.adaptive_error))
        ->group(lab);
    cmd->add_option("--guide-rays", o.settings.cache.guide_rays,
                    "Rays per record aimed at the brightest directly lit places (photons from the lights find "
                    "them), beside the MxN strata, combined by multiple importance sampling; 0: none; default " +
                        std::to_string(cache_defaults.guide_rays) + " (at most 4096)")
        ->group(lab);
    cmd->add_option("--spp", o.settings.path.samples, "Path samples per pixel (--gi path; 1 to 1048576)");
    cmd->add_option("--glossy-samples", o.settings.glossy_samples,
                    "Cache methods: samples of a glossy pixel's specular lobe for its indirect light, per "
                    "output pixel: on average over the frame, spent where the estimated error is largest "
                    "(with --glossy-uniform, in every glossy pixel); default " +
                        std::to_string(RenderSettings{}.glossy_samples) + ", at most 65536")
        ->group(lab);
    cmd->add_option("--hsh-order", o.settings.hsh_order,
                    "Splat: hemispherical-harmonic order of the radiance-cached lobes (n^2 coefficients a "
                    "channel, 1.." +
                        std::to_string(HSH_MAX_ORDER) + "); default: chosen from their roughness")
        ->group(lab);
    cmd->add_flag("--stratified", o.settings.path.stratified,
                  "Path tracing: draw each pixel's samples from a stratified grid over the hemisphere");
    cmd->add_option("--bounce-method", bounce_method,
                    "Cache methods, --bounces 2 or more: how a record's ray finds the bounces after the first: "
                    "path (continue its path) or photons (read a photon map at its hit); default auto: photons "
                    "unless the scene has a sky or an environment map")
        ->group(lab);
    cmd->add_option("--photons", o.settings.photon_paths,
                    "Photons shot for --bounce-method photons; default: rounds of " +
                        std::to_string(kPhotonMapPhotons) + " / (bounces - 1) until the map holds about " +
                        std::to_string(kPhotonMapPhotons) + " (at most " + std::to_string(kPhotonRounds) +
                        " rounds; 0 too; at most 67108864)")
        ->group(lab);
    cmd->add_flag("--light-uniform", light_uniform,
                  "Cache methods: every pixel takes --light-samples on area lights and the environment's peak, rather "
                  "than the frame's average spent in rounds where the estimated error gains most (the default)")
        ->group(lab);
    cmd->add_flag("--glossy-uniform", glossy_uniform,
                  "Every glossy pixel takes --glossy-samples, rather than the frame's average spent in rounds where "
                  "the estimated error gains most (the default)")
        ->group(lab);
    cmd->add_flag("--glossy-paths", glossy_paths,
                  "Glossy pixels' samples continue their paths past every hit, rather than reading the cache's "
                  "records where they land on a rough surface a record reaches (the default)")
        ->group(lab);
    cmd->add_option("--caustic-photons", o.settings.caustic_photons,
                    "Cache methods, scenes with a sharp glossy lobe: photons shot for the caustic map, which "
                    "carries light reflected by a glossy surface onto rough ones to the pixels (0: none, the "
                    "records' rays count it; at most 67108864); default " +
                        std::to_string(o.settings.caustic_photons))
        ->group(lab);
    cmd->add_option("--photon-min-support", o.settings.photon_min_support,
                    "--bounce-method photons: record rays whose hit's photon estimate summed fewer photons than "
                    "this continue their path instead of reading the map (0: never); default " +
                        shortest(o.settings.photon_min_support))
        ->group(lab);
    cmd->add_option("--short-ray-paths", o.settings.short_ray_paths,
                    "--bounce-method photons: record rays landing closer than this many photon-map gather radii "
                    "continue their path one bounce and read the map there (0: every ray reads it where it "
                    "lands); default " +
                        shortest(o.settings.short_ray_paths))
        ->group(lab);
  }

  // After parsing: the strings parsed into the settings, then the quality preset under the options given.
  void apply(CLI::App* cmd, RenderOptions& o) const {
    o.settings.gi = parse_gi_method(gi);
    if (!bounce_method.empty()) o.settings.bounce_method = parse_bounce_method(bounce_method);
    if (!hemisphere.empty()) parse_hemisphere(hemisphere, o.settings.cache);
    if (!spacing.empty()) parse_spacing(spacing, o.settings.cache);
    if (!fine_hemisphere.empty()) parse_hemisphere(fine_hemisphere, o.settings.cache, true);
    o.settings.glossy_reads_records = !glossy_paths;
    o.settings.glossy_adaptive = !glossy_uniform;
    o.settings.light_adaptive = !light_uniform;
    apply_quality(o.quality, o.settings, [&](const char* option) { return cmd->count(option) > 0; });
  }
};

}  // namespace

int main(int argc, char** argv) {
  keep_freed_host_memory();
  // `render --help-all`: --help with the experiment options shown too (their group is hidden otherwise).
  std::vector<char*> args(argv, argv + argc);
  bool help_all = false;
  static char help[] = "--help";
  for (char*& a : args)
    if (std::string(a) == "--help-all") {
      help_all = true;
      a = help;
    }
  argc = int(args.size());
  argv = args.data();
  // Options kept for measuring the method (benchmarks/RESULTS.md says what each bought), not for rendering.
  const std::string lab = help_all ? "Experiment options (measured in benchmarks/RESULTS.md)" : "";
  CLI::App app{"rcsplat: global illumination by radiance cache splatting on OpenCL devices"};
  app.require_subcommand(1);
  app.fallthrough();  // -q may follow the subcommand
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "Print only the summary and errors");

  DevicesOptions devices;
  CLI::App* devices_cmd = app.add_subcommand("devices", "List OpenCL platforms and devices, and whether rcsplat can use them");
  devices_cmd->add_option("--json", devices.json_path, "Also write the list as JSON");

  RenderOptions render;
  CameraFlags render_camera;
  EnvironmentFlags render_environment;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a glTF scene (default: the built-in Cornell box)");
  add_frame_options(render_cmd, render, render_camera, render_environment, lab);
  render_cmd->add_flag("--denoise", render.denoise,
                       "Denoise the light each pixel samples itself (area and environment direct light, sharp glossy "
                       "lobes; path tracing: the whole image) with Intel Open Image Denoise, and compose it with the "
                       "cache's indirect light, which stays as it is; the EXR keeps the noisy layers too (noisy, "
                       "noisy_direct, noisy_glossy, noisy_indirect). Needs the library: bash scripts/install-oidn.sh");
  if (!help_all) render_cmd->footer("--help-all also lists the experiment options.");
  RenderMethodFlags render_method;
  render_method.add(render_cmd, render, lab);

  AnimateOptions animate;
  CameraFlags animate_camera;
  EnvironmentFlags animate_environment;
  RenderMethodFlags animate_method;
  CLI::App* animate_cmd = app.add_subcommand(
      "animate",
      "Render a camera path to a frame sequence: the scene's glTF camera animation, a keyframe file or an "
      "orbit (default scene: the built-in Cornell box, which needs --orbit or --keyframes)");
  add_frame_options(animate_cmd, animate.render, animate_camera, animate_environment, lab);
  // A cache pre-pass or merge may render no image: run_animate asks for -o where frames are written.
  animate_cmd->get_option("--output")->required(false);
  animate_method.add(animate_cmd, animate.render, lab);
  animate_cmd->add_option("--keyframes", animate.keyframes,
                          "Camera path from a keyframe file: a line a key, \"time ex ey ez tx ty tz ux uy uz fov\" "
                          "(docs/USAGE.md)");
  animate_cmd->add_option("--orbit", animate.orbit_seconds,
                          "Camera path: one turn around the camera's target in this many seconds (--eye, --target "
                          "and --up set where it starts)");
  animate_cmd->add_option("--orbit-degrees", animate.orbit_degrees,
                          "--orbit: the arc swept in its seconds, in degrees (default 360: a whole turn; negative: "
                          "clockwise seen from above)");
  animate_cmd
      ->add_option("--animation", animate.animation,
                   "Without --keyframes or --orbit: the scene's glTF animation that moves --camera (default 0)")
      ->check(CLI::NonNegativeNumber);
  animate_cmd->add_option("--fps", animate.fps, "Frames a second of the path's time (default 24)");
  animate_cmd->add_option("--first-frame", animate.first_frame, "First frame rendered (default 0)")
      ->check(CLI::NonNegativeNumber);
  animate_cmd->add_option("--last-frame", animate.last_frame, "Last frame rendered (default: the path's end)")
      ->check(CLI::NonNegativeNumber);
  animate_cmd->add_flag("--cache-per-frame", animate.cache_per_frame,
                        "Place every frame's records anew, as `render` does (the default keeps the irradiance records "
                        "across frames and places new ones only where none reaches)");
  animate_cmd->add_flag("--cache-fixed", animate.cache_fixed,
                        "With --cache-in: every frame starts from the file's records alone (what a frame places is "
                        "not kept for the next), so a frame is the same bits whatever range of frames a process "
                        "renders: a walkthrough split over processes or machines (docs/USAGE.md, \"Cache files\")");
  animate_cmd->add_flag("--skip-existing", animate.skip_existing,
                        "Render only the frames whose output files are not all there already: a rerun or requeue of "
                        "a stopped task (outputs are written whole or not at all); needs --cache-fixed or "
                        "--cache-per-frame, so that no frame depends on the frames before it");
  animate_cmd
      ->add_option("--cache-every", animate.cache_every,
                   "The cache pre-pass of a walkthrough split over tasks: render only the range's frames that K divides "
                   "(key frames), each from no records, and write their records, tagged by key frame, to --cache-out "
                   "(-o optional); merge the tasks' files with --cache-merge (docs/FARM.md)")
      ->check(CLI::Range(1LL, 1000000LL));
  animate_cmd->add_option("--cache-merge", animate.cache_merge,
                          "Merge these --cache-every files into --cache-out and render nothing: the same records in "
                          "the same order whatever the split, a record dropped where an earlier key frame's records "
                          "reach it (docs/FARM.md)")
      ->expected(1, -1);
  animate_cmd
      ->add_option("--kept-records", animate.kept_records,
                   "Most irradiance records kept across frames; the least recently used go first (default "
                   "1048576, 160 bytes each)")
      ->check(CLI::Range(size_t(1), size_t(1) << 28));
  animate_cmd->add_option("--stats", animate.stats_path,
                          "Also write a CSV row a frame: time per pass, records, rays, device and host memory");
  animate_cmd->add_option("--mp4", animate.mp4_path,
                          "Also write an MP4 preview of the PNG frames with ffmpeg (H.264; needs ffmpeg installed)");

  RenderOptions reference;
  CameraFlags reference_camera;
  EnvironmentFlags reference_environment;
  reference.settings.gi = GiMethod::path;
  reference.settings.path.samples = 1024;
  reference.settings.path.stratified = true;
  reference.settings.preferred_pixel_samples = kReferencePixelSamples;
  bool light_samples_given = false;
  CLI::App* reference_cmd =
      app.add_subcommand("reference", "Path-trace a converged reference (same materials, lights and bounce count)");
  add_frame_options(reference_cmd, reference, reference_camera, reference_environment, lab);
  reference_cmd->add_option("--spp", reference.settings.path.samples,
                            "Samples per pixel (default 1024); the light "
                            "samples default to the same number");
  reference_cmd->add_flag("--resume", reference.resume,
                          "Add samples to the .exr output an earlier run wrote, up to --spp in all");
  reference_cmd->callback([&] { light_samples_given = reference_cmd->count("--light-samples") > 0; });

  FlickerOptions flicker;
  CLI::App* flicker_cmd =
      app.add_subcommand("flicker",
                         "How much a frame sequence's light changes between consecutive frames where both see the same "
                         "surface (temporal relMSE after reprojection by the position layer), less a reference's");
  flicker_cmd->add_option("frames", flicker.frames, "The frames, as animate wrote them (.exr pattern: frames/%04d.exr)")
      ->required();
  flicker_cmd->add_option("--reference", flicker.reference,
                          "A reference sequence of the same path (pattern): its own flicker is subtracted");
  flicker_cmd->add_option("--positions", flicker.positions,
                          "Take each frame's position, depth and camera from this sequence (pattern) of the same "
                          "frames: for a denoised sequence, whose EXRs hold only colours");
  flicker_cmd->add_option("--first-frame", flicker.first_frame, "First frame (default 0)")
      ->check(CLI::NonNegativeNumber);
  flicker_cmd->add_option("--last-frame", flicker.last_frame, "Last frame (default: up to the first missing one)")
      ->check(CLI::NonNegativeNumber);
  flicker_cmd->add_option("--layer", flicker.layer, "Layer judged: indirect (default) or full")
      ->check(CLI::IsMember({"indirect", "full"}));
  flicker_cmd->add_flag("--demodulate", flicker.demodulate,
                        "Judge the layer divided by the albedo layer (pixels of albedo below 0.02 left out): textures "
                        "do not flicker, but the nearest pixel does not reproject them exactly either");
  flicker_cmd->add_option("--json", flicker.json_path, "Also write the numbers, a pair of frames each, as JSON");

  InfoOptions info;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "What a scene contains and what rcsplat will simulate for it, with the kernel switches it compiles");
  info_cmd->add_option("scene", info.scene_path, "glTF 2.0 scene (.gltf or .glb); default: the built-in Cornell box");
  info_cmd->add_option("--json", info.json_path, "Also write it as JSON");
  info_cmd->add_option("--device", info.device,
                       "OpenCL device for the bounce probe (the bounce count a render chooses); without one, info "
                       "says so and prints the rest");
  EnvironmentFlags info_environment;
  info_environment.add(info_cmd, info.environment);
  add_scene_limit_options(info_cmd, info.limits, false);

  CompareOptions compare;
  CLI::App* compare_cmd = app.add_subcommand("compare", "Error of an image against a reference: relMSE, RMSE, MAE, relMSE of block means, FLIP");
  compare_cmd->add_option("image", compare.image_path, "The image to judge (.exr)")->required();
  compare_cmd->add_option("reference", compare.reference_path, "The reference (.exr)")->required();
  compare_cmd->add_option("--heatmap", compare.heatmap_path, "Write a false-colour per-pixel relMSE image (.png)");
  compare_cmd->add_option("--flip-heatmap", compare.flip_heatmap_path, "Write the per-pixel FLIP image (.png, magma)");
  compare_cmd->add_option("--heatmap-layer", compare.heatmap_layer, "Layer the heat maps show: full (default) or indirect")
      ->check(CLI::IsMember({"full", "indirect"}));
  compare_cmd->add_option("--exposure", compare.exposure, "Exposure in stops of the tone mapping FLIP judges (as for PNGs)");
  compare_cmd->add_option("--json", compare.json_path, "Also write the numbers as JSON");
  compare_cmd->add_option("--block", compare.block,
                          "Also relMSE of BxB pixel means (default 8): noise averages out, a cache's blotches do not")
      ->check(CLI::Range(1, 4096));

  SweepOptions sweep;
  EnvironmentFlags sweep_environment;
  CLI::App* sweep_cmd = app.add_subcommand(
      "sweep", "What accuracy costs in time: cache settings and path tracing against a reference, as a CSV and a plot");
  sweep_cmd->add_option("scene", sweep.scene_path, "glTF 2.0 scene (default: the built-in Cornell box)");
  sweep_cmd->add_option("--reference", sweep.reference_path,
                        "Converged reference (.exr from `rcsplat reference`): the frame size and bounces follow it")
      ->required();
  sweep_cmd->add_option("-o,--output", sweep.output_dir, "Folder for sweep.csv, accuracy_vs_time.png and the images")
      ->required();
  sweep_cmd->add_option("--device", sweep.device, "OpenCL device: index or name substring");
  sweep_cmd->add_option("--accuracy", sweep.accuracies, "Cache accuracies (default 0.15,0.3,0.6; none: --accuracy \"\")")
      ->delimiter(',')->expected(0, 64);
  sweep_cmd->add_option("--hemisphere", sweep.hemispheres, "Rays per record, MxN each (default 16x32)")
      ->delimiter(',')->expected(0, 64);
  sweep_cmd->add_option("--hsh-order", sweep.hsh_orders, "HSH orders of radiance-cached lobes (default: chosen)")
      ->delimiter(',')->expected(0, 64)->check(CLI::Range(1u, unsigned(HSH_MAX_ORDER)));
  sweep_cmd->add_option("--path-spp", sweep.path_samples,
                        "Stratified path tracing at these samples per pixel (default 4,16,64; none: --path-spp \"\")")
      ->delimiter(',')->expected(0, 64);
  sweep_cmd->add_option("--denoise", sweep.denoise,
                        "Path tracing plus Intel Open Image Denoise (pyoidn, benchmarks/denoise.py) beside plain: "
                        "auto (when the benchmark Python has it; default), on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  sweep_cmd->add_flag("!--no-plot", sweep.plot, "Do not draw accuracy_vs_time.png");
  sweep_cmd->add_option("--light-samples", sweep.light_samples, "Light samples per pixel (default 16)")
      ->check(CLI::Range(0u, 1u << 20));
  sweep_cmd->add_option("--pixel-samples", sweep.pixel_samples, "Primary samples per pixel (default: as render)")
      ->check(CLI::Range(1u, 64u));
  sweep_cmd->add_option("--bounces", sweep.bounces, "Indirect bounces (default: the reference's)")
      ->check(CLI::Range(1u, unsigned(kMaxBounces)));
  sweep_cmd->add_option("--camera", sweep.camera, "Index of the scene camera to use")->check(CLI::NonNegativeNumber);
  sweep_cmd->add_option("--block", sweep.block, "Block size of block relMSE (default 8)")->check(CLI::Range(1, 4096));
  sweep_environment.add(sweep_cmd, sweep.environment);
  add_scene_limit_options(sweep_cmd, sweep.limits, true);

  BenchOptions bench;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "The same frame on each OpenCL device (kernel builds, time per pass, memory), or --traversal");
  bench_cmd->add_option("scene", bench.scene_path,
                        "glTF scene (default: the built-in Cornell box; for --traversal ../shared/scenes Sponza, else a "
                        "generated one)");
  bench_cmd->add_option("--devices", bench.devices,
                        "Devices to compare: all (every usable one) or a comma-separated list of indices or name parts; "
                        "default: the default device");
  bench_cmd->add_option("--device", bench.device, "One OpenCL device: index or name substring");
  bench_cmd->add_option("--width", bench.width, "Frame width (default 1024)")->check(CLI::Range(1, 16384));
  bench_cmd->add_option("--height", bench.height, "Frame height (default 768)")->check(CLI::Range(1, 16384));
  bench_cmd->add_flag("--traversal", bench.traversal,
                      "Instead: the traversal kernel against Embree's rtcIntersect1 on the same rays");
  bench_cmd->add_option("--rays", bench.rays, "--traversal: rays in the incoherent pattern")
      ->check(CLI::Range(size_t(1), size_t(1) << 26));
  bench_cmd->add_option("--record-points", bench.record_points, "--traversal: points for the 256-ray record pattern")
      ->check(CLI::Range(size_t(1), size_t(1) << 18));
  bench_cmd->add_option("--repeats", bench.repeats,
                        "Timed frames per device (default 3), or --traversal's paired runs (default 5); medians")
      ->check(CLI::Range(1, 1000));
  bench_cmd->add_option("--json", bench.json_path, "Also write the results as JSON");
  add_scene_limit_options(bench_cmd, bench.limits, false);

  CLI11_PARSE(app, argc, argv);
  set_quiet(quiet);
  try {
    if (*devices_cmd) return run_devices(devices);
    if (*render_cmd) {
      render_camera.apply(render.settings);
      render_environment.apply(render.environment);
      render_method.apply(render_cmd, render);
      return run_render(render);
    }
    if (*animate_cmd) {
      animate_camera.apply(animate.render.settings);
      animate_environment.apply(animate.render.environment);
      animate_method.apply(animate_cmd, animate.render);
      return run_animate(animate);
    }
    if (*reference_cmd) {
      reference_camera.apply(reference.settings);
      reference_environment.apply(reference.environment);
      if (!light_samples_given) reference.settings.light_samples = reference.settings.path.samples;
      return run_render(reference);
    }
    if (*compare_cmd) return run_compare(compare);
    if (*flicker_cmd) return run_flicker(flicker);
    if (*info_cmd) {
      info_environment.apply(info.environment);
      return run_info(info);
    }
    if (*sweep_cmd) {
      sweep_environment.apply(sweep.environment);
      return run_sweep(sweep);
    }
    if (*bench_cmd) {
      if (!bench.traversal && bench_cmd->count("--repeats") == 0) bench.repeats = 3;
      return run_bench(bench);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", printable(e.what()).c_str());
    return 1;
  } catch (const cl::Error& e) {
    // Devices may allocate lazily: running out then shows at a launch or a transfer, not at the allocation.
    if (is_out_of_memory(e.err()))
      std::fprintf(stderr, "error: out of device memory: OpenCL call %s failed with code %d; render fewer pixels "
                           "(--width, --height) or choose another --device\n", e.what(), e.err());
    else
      std::fprintf(stderr, "error: OpenCL call %s failed with code %d\n", e.what(), e.err());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of host memory: this machine could not hold the frame beside the scene; render "
                         "fewer pixels (--width, --height), or lower --max-host-memory so that a scene too large is "
                         "refused as it is read\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", printable(e.what()).c_str());
    return 1;
  }
  return 0;
}
