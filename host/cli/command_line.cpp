#include "cli/command_line.h"

#include <cmath>
#include <cstdio>
#include <new>

#include "kernels/hsh.h"
#include "render/bounce_choice.h"
#include "render/frame_plan.h"
#include "render/pixel_samples.h"
#include "util/error.h"

namespace rcsplat {

namespace {

std::optional<glm::vec3> as_vec3(const std::vector<float>& v) {
  if (v.empty()) return std::nullopt;
  return glm::vec3(v[0], v[1], v[2]);
}

}  // namespace

std::string shortest(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(v));
  return text;
}

void CameraFlags::apply(RenderSettings& s) const {
  s.camera_overrides.eye = as_vec3(eye);
  s.camera_overrides.target = as_vec3(target);
  s.camera_overrides.up = as_vec3(up);
  s.camera_overrides.fov_degrees = fov;
}

void EnvironmentFlags::add(CLI::App* cmd, EnvironmentSettings& e) {
    cmd->add_option("--sky", sky, "Uniform sky radiance R,G,B seen by every ray that leaves the scene")
        ->delimiter(',')
        ->expected(3);
    cmd->add_option("--environment", e.file,
                    "Equirectangular environment map (.exr, .hdr): +Y up, its centre column toward -Z; its bright "
                    "peak (a sun) is importance-sampled by shadow rays, the rest gathered with the indirect light");
    cmd->add_option("--environment-intensity", e.intensity,
                    "Multiplies the environment map (default " + shortest(EnvironmentSettings{}.intensity) + ")");
    cmd->add_option("--environment-rotation", e.rotation_degrees,
                    "Rotates the environment map about +Y by this many degrees (default " +
                        shortest(EnvironmentSettings{}.rotation_degrees) + ")");
    cmd->add_option("--light-through-glass", light_through_glass,
                    "How the lights reach what lies behind glass: 'straight' (default: shadow rays pass every glass "
                    "with its colour; exact for thin-walled glass, and free of noise) or 'caustics' (a glass volume "
                    "stops shadow rays and its light comes by a caustic map, so a glass ball or vase focuses it)")
        ->check(CLI::IsMember({"straight", "caustics"}));
    cmd->add_option("--glass-caustic-photons", e.glass.photons,
                    "Photon paths for --light-through-glass caustics (default " +
                        std::to_string(GlassLight{}.photons) + ")")
        ->check(CLI::Range(1u, kMaxPhotonPaths));
}

void EnvironmentFlags::apply(EnvironmentSettings& e) const {
  e.sky = as_vec3(sky);
  e.glass.caustics = light_through_glass == "caustics";
}

void add_scene_limit_options(CLI::App* cmd, SceneLimits& limits, bool device) {
  cmd->add_option("--asset-root", limits.asset_roots,
                  "Also let the scene read files inside this folder (through '..' or symbolic links); for a scene you "
                  "trust (default: only the scene's own folder and the folders under it)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--max-triangles", limits.max_triangles,
                  "Refuse a scene that places more triangles, instances counted (default " +
                      std::to_string(SceneLimits{}.max_triangles) + ")")
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

void add_frame_options(CLI::App* cmd, RenderJob& o, std::string& json_path, bool& progress_lines, CameraFlags& cam,
                       EnvironmentFlags& env, const HelpGroups& groups) {
  const std::string& lab = groups.lab;
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
                  "Samples per pixel on emissive triangles (rounded up to a square; 0 to " +
                      std::to_string(kMaxLightSamples) + ")");
  cmd->add_option("--seed", o.settings.seed, "Seed of the sample pattern");
  cmd->add_option("--pixel-samples", o.settings.pixel_samples,
                  "Primary samples per pixel, a square number (4: a 2x2 sub-pixel grid) for anti-aliased edges; light "
                  "and path samples are per pixel, records are those of one sample; default " +
                      std::to_string(RenderSettings{}.preferred_pixel_samples) + " for render, " +
                      std::to_string(kReferencePixelSamples) +
                      " for reference (a finer grid, so compare counts a render's edge aliasing as error), fewer "
                      "where --spp "
                  "does not divide by them or the frame is very large; path tracing takes each sample at a random "
                  "point of its cell of the grid, so it integrates over the pixel's area");
  cmd->add_flag("!--sub-pixel-grid", o.settings.path.pixel_area,
                "Path tracing: take the pixel samples at the fixed points a cache render shades (a rotated grid, one "
                "point in each cell of the s x s grid) instead of a random point of each cell")
      ->group(lab);
  cmd->add_option("--bounces", o.settings.bounces,
                  "Indirect bounces: 1 lights the first bounce's hit directly, each more adds a reflection (every "
                  "method, the reference too); default 0: chosen from the scene, the fewest that leave out at most " +
                      std::to_string(int(std::lround(100.0 * kMissingIndirectShare))) +
                      "% of the indirect light, as a few photons measure it (at most " +
                      std::to_string(kMaxChosenBouncesPhotons) + "; " + std::to_string(kMaxChosenBouncesPath) +
                      " with --sky or --environment); at most " + std::to_string(kMaxBounces));
  env.add(cmd, o.environment);
  add_scene_limit_options(cmd, o.limits, true);
  cmd->add_option("--exposure", o.exposure, "PNG exposure in stops");
  cmd->add_option("--json", json_path, "Also write the summary as JSON");
  cmd->add_flag("--progress-lines", progress_lines,
                "Also print the command's progress as lines \"Progress: NN%\" on stdout, as render-farm managers "
                "(Deadline and others) read it");
}

void RenderMethodFlags::add(CLI::App* cmd, RenderJob& o, std::string& quality, const HelpGroups& groups) {
  const std::string& lab = groups.lab;
  cmd->add_option("--cache-in", o.cache_in,
                  "Splat: start from the irradiance records of a cache file that --cache-out wrote for this scene "
                  "and these settings")
      ->check(CLI::ExistingFile);
  cmd->add_option("--cache-out", o.cache_out,
                  "Splat: write the irradiance records kept after the last frame to this cache file");
  cmd->add_option("--quality", quality,
                  "Quality preset: draft (a quick look: " + quality_preset_description("draft") +
                      "), standard (the defaults), final (" + quality_preset_description("final") +
                      "); options given on the command line win")
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
                      std::to_string(cache_defaults.guide_rays) + " (at most " + std::to_string(kMaxGuideRays) + ")")
      ->group(lab);
  cmd->add_option("--spp", o.settings.path.samples,
                  "Path samples per pixel (--gi path; 1 to " + std::to_string(kMaxPathSamples) + ")");
  cmd->add_option("--glossy-samples", o.settings.glossy_samples,
                  "Cache methods: samples of a glossy pixel's specular lobe for its indirect light, per "
                  "output pixel: on average over the frame, spent where the estimated error is largest "
                  "(with --glossy-uniform, in every glossy pixel); default " +
                      std::to_string(RenderSettings{}.glossy_samples) + ", at most " + std::to_string(kMaxGlossySamples))
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
                      " rounds; 0 too; at most " + std::to_string(kMaxPhotonPaths) + ")")
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
                  "records' rays count it; at most " + std::to_string(kMaxPhotonPaths) + "); default " +
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

void RenderMethodFlags::apply(CLI::App* cmd, RenderJob& o, const std::string& quality) const {
  o.settings.gi = parse_gi_method(gi);
  if (!bounce_method.empty()) o.settings.bounce_method = parse_bounce_method(bounce_method);
  if (!hemisphere.empty()) parse_hemisphere(hemisphere, o.settings.cache);
  if (!spacing.empty()) parse_spacing(spacing, o.settings.cache);
  if (!fine_hemisphere.empty()) parse_hemisphere(fine_hemisphere, o.settings.cache, true);
  o.settings.glossy_reads_records = !glossy_paths;
  o.settings.glossy_adaptive = !glossy_uniform;
  o.settings.light_adaptive = !light_uniform;
  apply_quality(quality, o.settings, [&](const char* option) { return cmd->count(option) > 0; });
}

HelpGroups help_groups(std::vector<char*>& args) {
  static char help[] = "--help";
  HelpGroups groups;
  for (char*& a : args)
    if (std::string(a) == "--help-all") {
      groups.help_all = true;
      a = help;
    }
  // Options kept for measuring the method (benchmarks/RESULTS.md says what each bought), not for rendering.
  if (groups.help_all) groups.lab = "Experiment options (measured in benchmarks/RESULTS.md)";
  return groups;
}

int run_reporting_errors(const std::function<int()>& run) {
  try {
    return run();
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", printable(e.what()).c_str());
  } catch (const cl::Error& e) {
    // Devices may allocate lazily: running out then shows at a launch or a transfer, not at the allocation.
    if (is_out_of_memory(e.err()))
      std::fprintf(stderr, "error: out of device memory: OpenCL call %s failed with code %d; render fewer pixels "
                           "(--width, --height) or choose another --device\n", e.what(), e.err());
    else
      std::fprintf(stderr, "error: OpenCL call %s failed with code %d\n", e.what(), e.err());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of host memory: this machine could not hold the frame beside the scene; render "
                         "fewer pixels (--width, --height), or lower --max-host-memory so that a scene too large is "
                         "refused as it is read\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", printable(e.what()).c_str());
  }
  return 1;
}

}  // namespace rcsplat
