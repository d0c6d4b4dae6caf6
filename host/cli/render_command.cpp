#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "cli/command_line.h"
#include "cli/commands.h"
#include "image/image_io.h"
#include "render/denoise_frame.h"
#include "render/render_output.h"
#include "kernels/hsh.h"
#include "render/bounce_choice.h"
#include "render/frame_plan.h"
#include "render/pixel_samples.h"
#include "util/atomic_file.h"
#include "util/byte_size.h"
#include "util/error.h"
#include "util/log.h"
#include "util/paths.h"

namespace rcsplat {
namespace {

double mrays_per_second(uint64_t rays, double seconds) { return seconds > 0 ? double(rays) / seconds * 1e-6 : 0.0; }

// How the glossy pixels were sampled, in the summary's words.
std::string glossy_samples_text(const GlossyStats& g) {
  char text[200];
  if (!g.adaptive) {
    std::snprintf(text, sizeof text, "%u lobe samples each", g.samples);
  } else {
    std::snprintf(text, sizeof text,
                  "%.1f lobe samples each on average (budget %u; %u rounds by estimated error, up to %u; %llu pixels "
                  "refined)",
                  g.mean_samples, g.samples, g.rounds, g.most_samples, (unsigned long long)g.refined_pixels);
  }
  return text;
}

// Device buffers at the frame's peak, largest first, and the process's peak resident memory.
void print_memory(const DeviceMemoryUse& device) {
  std::vector<std::pair<size_t, std::string>> uses;
  for (const auto& [use, bytes] : device.at_peak_by_use) uses.push_back({bytes, use});
  std::sort(uses.rbegin(), uses.rend());
  std::printf("memory       device peak %s:", byte_size(double(device.peak_bytes), "MiB").c_str());
  for (size_t i = 0; i < uses.size() && i < 6; ++i)
    std::printf("%s %s %s", i ? "," : "", uses[i].second.c_str(), byte_size(double(uses[i].first), "MiB").c_str());
  if (uses.size() > 6) std::printf(", %zu more", uses.size() - 6);
  std::printf("; host peak %s\n", byte_size(double(peak_host_bytes()), "MiB").c_str());
}

nlohmann::json memory_json(const DeviceMemoryUse& device) {
  return {{"device_peak_bytes", device.peak_bytes}, {"device_at_peak_by_use", device.at_peak_by_use},
          {"host_peak_bytes", peak_host_bytes()}};
}

void print_summary(const Scene& scene, const ScenePlan& plan, const RenderedImage& image,
                   const RenderSettings& settings, const std::vector<std::string>& outputs) {
  const RenderStats& s = image.stats;
  std::printf("scene        %s\n", scene.source.c_str());
  print_scene_plan(plan, s.scene.bvh_depth);  // what `rcsplat info` prints
  std::printf("device       %s\n", s.device.c_str());
  std::printf("image        %d x %d, %u light samples per pixel, indirect light: %s, %u bounce%s\n", image.width,
              image.height, s.primary.light_samples, gi_method_name(s.gi), s.bounces.count,
              s.bounces.count == 1 ? "" : "s");
  if (s.bounces.chosen)
    std::printf("bounces      %u chosen from the scene: each reflection keeps %.0f%% of the light it receives (photons "
                "measured it), so the bounces left out carry at most %.0f%% of the indirect light (--bounces)\n",
                s.bounces.count, 100.0 * s.bounces.kept_per_bounce, 100.0 * kMissingIndirectShare);
  if (s.gi == GiMethod::path && settings.path.pixel_area)
    std::printf(
        "pixels       %u primary sample%s each, at random points of the cells of a %ux%u grid over the pixel "
        "(%u rounds of the frame, averaged: the pixel's area integral)\n",
        s.primary.pixel_samples, s.primary.pixel_samples == 1 ? "" : "s", pixel_sample_side(s.primary.pixel_samples),
        pixel_sample_side(s.primary.pixel_samples), s.primary.pixel_samples);
  else if (s.primary.pixel_samples > 1 && s.gi != GiMethod::splat && s.gi != GiMethod::octree)
    std::printf(
        "pixels       %u primary samples each (a %ux%u sub-pixel grid, rendered as a %d x %d frame and "
        "averaged)\n",
        s.primary.pixel_samples, pixel_sample_side(s.primary.pixel_samples), pixel_sample_side(s.primary.pixel_samples),
        image.width * int(pixel_sample_side(s.primary.pixel_samples)),
        image.height * int(pixel_sample_side(s.primary.pixel_samples)));
  else if (s.primary.pixel_samples > 1)
    std::printf(
        "pixels       %u primary samples each (a %ux%u sub-pixel grid, rendered as a %d x %d frame and "
        "averaged); record reach and placement spacing are in output pixels (spacings below are in sub-pixels), "
        "and placement stops one output pixel apart, so the records are those one sample places; %llu sub-pixels "
        "no record reached (edges) took the best-weighted record near them\n",
        s.primary.pixel_samples, pixel_sample_side(s.primary.pixel_samples), pixel_sample_side(s.primary.pixel_samples),
        image.width * int(pixel_sample_side(s.primary.pixel_samples)),
        image.height * int(pixel_sample_side(s.primary.pixel_samples)),
        (unsigned long long)s.irradiance.filled_sub_pixels);
  std::printf("BVH          %zu nodes, %zu triangle blocks, depth %d\n", s.scene.bvh_nodes, s.scene.bvh_blocks,
              s.scene.bvh_depth);
  if (s.scene.glass_caustics)
    std::printf("glass light  by the glass caustic map (--light-through-glass caustics): %llu photons of %u paths "
                "passed a glass volume, radii %.4g to %.4g (each photon's holds its neighbours), %.3f s\n",
                (unsigned long long)s.scene.glass_caustic_photons, s.scene.glass_caustic_paths,
                s.scene.glass_caustic_radius, s.scene.glass_caustic_largest_radius, s.scene.glass_caustic_s);
  std::printf("rays         %llu primary, %llu shadow\n", (unsigned long long)s.primary.primary_rays,
              (unsigned long long)s.primary.shadow_rays);
  std::printf("time         BVH build %.3f s, upload %.3f s, kernel build %.3f s\n", s.scene.bvh_build_s,
              s.scene.upload_s, s.program_s);
  std::printf(
      "             G-buffer %.3f s, direct light %.3f s (%.2f Mrays/s)", s.primary.gbuffer_s, s.primary.direct_s,
      mrays_per_second(s.primary.primary_rays + s.primary.shadow_rays, s.primary.gbuffer_s + s.primary.direct_s));
  if (s.primary.light_rounds)
    std::printf("; light samples in %u rounds by estimated error, %.1f per pixel on average, %llu pixels refined",
                s.primary.light_rounds, s.primary.light_mean_samples,
                (unsigned long long)s.primary.light_refined_pixels);
  std::printf("\n");
  if (s.gi == GiMethod::splat || s.gi == GiMethod::octree) {
    const CacheSettings& c = settings.cache;
    std::printf("cache        a = %g, %ux%u rays per record", c.accuracy, c.theta_strata, c.phi_strata);
    if (c.fine_theta_strata) std::printf(" (%ux%u at spacing 1)", c.fine_theta_strata, c.fine_phi_strata);
    std::printf(", record spacing %g..%g pixels, ", c.min_reach_pixels, c.max_reach_pixels);
    if (c.adaptive_error > 0.0f)
      std::printf("adaptive rays (%ux%u first, all where the error score is above %g: %llu records), ",
                  c.theta_strata / 2, c.phi_strata / 2, c.adaptive_error,
                  (unsigned long long)s.irradiance.adaptive_records);
    if (c.hessian_error > 0.0f) std::printf("radii from the occlusion Hessian (error budget %g)\n", c.hessian_error);
    else std::printf("radii from Ward's split sphere\n");
    if (s.photon_map.photons)
      std::printf(
          "photon map   bounces 2..%u at the records' hits: %llu landings after a reflection, from %llu photons shot; "
          "radius %.4g, record rays shorter than %.4g continue a bounce (%.3f s)\n",
          s.bounces.count, (unsigned long long)s.photon_map.photons, (unsigned long long)s.photon_map.paths,
          s.photon_map.radius, s.photon_map.radius * settings.short_ray_paths, s.photon_map.seconds);
    else if (s.bounces.count > 1)
      std::printf("bounces      2..%u at the records' hits by path continuation\n", s.bounces.count);
    if (s.caustics.paths)
      std::printf("caustic map  light -> glossy -> rough at the pixels: %llu landings after a glossy reflection, from "
                  "%llu photons shot; radius %.4g (%.3f s)\n",
                  (unsigned long long)s.caustics.photons, (unsigned long long)s.caustics.paths, s.caustics.radius,
                  s.caustics.seconds);
    if (s.guide.clusters)
      std::printf("light guide  %u rays per record at %u bright places found by %llu photons (%.3f s)\n", c.guide_rays,
                  s.guide.clusters, (unsigned long long)s.guide.photons, s.guide.seconds);
    else
      std::printf("light guide  none (%s)\n", c.guide_rays ? "no light with power" : "--guide-rays 0");
    std::printf("records      %llu:", (unsigned long long)s.irradiance.records);
    for (const PlacementLevel& l : s.irradiance.levels) std::printf(" %u at spacing %d;", l.records, l.spacing_pixels);
    std::printf(" %llu pixels left uncovered\n", (unsigned long long)s.irradiance.uncovered_pixels);
    std::printf("             reach at the minimum spacing: %.1f%%, at the maximum: %.1f%%\n",
                100.0 * double(s.irradiance.at_min_radius) / double(std::max<uint64_t>(s.irradiance.records, 1)),
                100.0 * double(s.irradiance.at_max_radius) / double(std::max<uint64_t>(s.irradiance.records, 1)));
    std::printf("             %llu rays (%.2f Mrays/s)\n", (unsigned long long)s.irradiance.rays,
                mrays_per_second(s.irradiance.rays, s.irradiance.records_s));
    std::printf("time         records %.3f s, placement %.3f s, splat %.3f s, resolve %.3f s\n", s.irradiance.records_s,
                s.irradiance.placement_s, s.irradiance.splat_s, s.irradiance.resolve_s);
    if (s.primary.rough_pixels || s.primary.glossy_pixels || s.glossy.rays)
      std::printf(
          "specular     %llu rough pixels from the irradiance; %llu glossy pixels, %s; per "
          "pixel (lobes, and the light guide's share of radiance-cached pixels): %llu rays, %.3f s (%.2f "
          "Mrays/s)%s\n",
          (unsigned long long)s.primary.rough_pixels, (unsigned long long)s.primary.glossy_pixels,
          glossy_samples_text(s.glossy).c_str(), (unsigned long long)s.glossy.rays, s.glossy.seconds,
          mrays_per_second(s.glossy.rays, s.glossy.seconds),
          s.glossy.reads_records ? "; the samples read the records where they land" : "");
    if (s.radiance.order)
      std::printf(
          "radiance     %llu radiance-cached pixels: HSH order %u (%u coefficients a channel, holds %.0f%% of the "
          "sharpest cached lobe), a = %g, %llu records, %llu rays (%.2f Mrays/s), %llu sub-pixels filled\n"
          "time         lobe table %.3f s, records %.3f s, placement %.3f s, splat %.3f s\n",
          (unsigned long long)s.primary.hsh_pixels, s.radiance.order, s.radiance.order * s.radiance.order,
          100.0 * s.radiance.captured_energy, double(s.radiance.accuracy), (unsigned long long)s.radiance.records,
          (unsigned long long)s.radiance.rays, mrays_per_second(s.radiance.rays, s.radiance.records_s),
          (unsigned long long)s.radiance.filled_sub_pixels, s.radiance.lobe_table_s, s.radiance.records_s,
          s.radiance.placement_s, s.radiance.splat_s);
  }
  if (s.gi == GiMethod::path) {
    std::printf("path         %u samples per pixel%s, %llu rays, %.3f s (%.2f Mrays/s)\n", s.path.samples,
                settings.path.stratified ? " (stratified)" : "", (unsigned long long)s.path.rays, s.path.seconds,
                mrays_per_second(s.path.rays, s.path.seconds));
  }
  if (!s.denoise.device.empty()) {
    std::printf("denoise      Open Image Denoise (%s device) on %s, %.3f s", s.denoise.device.c_str(),
                s.denoise.layers.empty() ? "nothing (the frame samples no light per pixel)" : s.denoise.layers.c_str(),
                s.denoise.seconds);
    if (s.denoise.indirect_only_s > 0)
      std::printf(" (of which the indirect layer, for measuring, %.3f s)", s.denoise.indirect_only_s);
    std::printf("\n");
  }
  print_memory(s.device_memory);
  std::printf("total        %.3f s (on the host between passes: bounce probe %.3f s, image layers %.3f s)\n",
              s.total_s, s.bounces.probe_s, s.primary.layers_s);
  for (const std::string& out : outputs) std::printf("wrote        %s\n", out.c_str());
}

// Non-finite values in the layers a user looks at (colour, direct, indirect): zero, by the renderer's promise.
size_t nonfinite_values(const RenderedImage& image) {
  size_t count = 0;
  for (const std::vector<float>* layer : {&image.color, &image.direct, &image.indirect})
    for (float v : *layer) count += !std::isfinite(v);
  return count;
}

nlohmann::json summary_json(const Scene& scene, const ScenePlan& plan, const RenderedImage& image,
                            const RenderSettings& settings, const std::vector<std::string>& outputs) {
  const RenderStats& s = image.stats;
  nlohmann::json j = {
      {"scene_plan", scene_plan_json(plan, s.scene.bvh_depth)},
      {"scene", scene.source},
      {"device", s.device},
      {"width", image.width},
      {"height", image.height},
      {"gi", gi_method_name(s.gi)},
      {"bounces", s.bounces.count},
      {"bounces_chosen", s.bounces.chosen},
      {"kept_per_bounce", s.bounces.kept_per_bounce},
      {"light_samples", s.primary.light_samples},
      {"light_rounds", s.primary.light_rounds},
      {"light_mean_samples", s.primary.light_mean_samples},
      {"light_refined_pixels", s.primary.light_refined_pixels},
      {"pixel_samples", s.primary.pixel_samples},
      {"pixel_points", pixel_points_name(settings)},
      {"triangles", s.scene.triangles},
      {"bvh", {{"nodes", s.scene.bvh_nodes}, {"blocks", s.scene.bvh_blocks}, {"depth", s.scene.bvh_depth}}},
      {"glass_caustics",
       s.scene.glass_caustics
           ? nlohmann::json{{"paths", s.scene.glass_caustic_paths}, {"photons", s.scene.glass_caustic_photons},
                            {"radius", s.scene.glass_caustic_radius},
                            {"largest_radius", s.scene.glass_caustic_largest_radius},
                            {"seconds", s.scene.glass_caustic_s}}
           : nlohmann::json(nullptr)},
      {"rays",
       {{"primary", s.primary.primary_rays},
        {"shadow", s.primary.shadow_rays},
        {"records", s.irradiance.rays},
        {"path", s.path.rays}}},
      {"seconds", {{"bvh_build", s.scene.bvh_build_s}, {"upload", s.scene.upload_s}, {"kernel_build", s.program_s},
                   {"gbuffer", s.primary.gbuffer_s}, {"direct", s.primary.direct_s},
                   {"records", s.irradiance.records_s}, {"placement", s.irradiance.placement_s},
                   {"splat", s.irradiance.splat_s}, {"resolve", s.irradiance.resolve_s}, {"path", s.path.seconds},
                   {"photon_map", s.photon_map.seconds}, {"caustic_map", s.caustics.seconds},
                   {"light_guide", s.guide.seconds},
                   {"glossy", s.glossy.seconds}, {"bounce_probe", s.bounces.probe_s},
                   {"layers", s.primary.layers_s}, {"denoise", s.denoise.seconds},
                   {"denoise_indirect_only", s.denoise.indirect_only_s}, {"total", s.total_s}}},
      {"denoise", {{"layers", s.denoise.layers}, {"device", s.denoise.device}}},
      {"memory", memory_json(s.device_memory)},
      {"outputs", outputs},
      {"not_simulated", scene.unsupported},
      {"nonfinite_values", nonfinite_values(image)},
      {"materials", {{"lambertian", s.scene.lambertian_materials}, {"rough", s.scene.rough_materials},
                     {"radiance_cached", s.scene.hsh_materials}, {"glossy", s.scene.glossy_materials},
                     {"brdf_compiled", s.scene.specular_brdf}, {"hsh_compiled", s.scene.hsh_materials > 0},
                     {"radiance_cached_min_roughness", HSH_MIN_ROUGHNESS}}}};
  if (s.gi == GiMethod::splat || s.gi == GiMethod::octree) {
    const CacheSettings& c = settings.cache;
    nlohmann::json levels = nlohmann::json::array();
    for (const PlacementLevel& l : s.irradiance.levels)
      levels.push_back({{"spacing", l.spacing_pixels}, {"records", l.records}});
    j["cache"] = {
        {"accuracy", c.accuracy},
        {"hemisphere", {c.theta_strata, c.phi_strata}},
        {"fine_hemisphere", {c.fine_theta_strata, c.fine_phi_strata}},
        {"spacing", {c.min_reach_pixels, c.max_reach_pixels}},
        {"radius_rule", c.hessian_error > 0.0f ? "occlusion_hessian" : "split_sphere"},
        {"hessian_error", c.hessian_error},
        {"adaptive_rays", {{"error", c.adaptive_error}, {"records_traced_again", s.irradiance.adaptive_records}}},
        {"records", s.irradiance.records},
        {"levels", levels},
        {"uncovered_pixels", s.irradiance.uncovered_pixels},
        {"filled_sub_pixels", s.irradiance.filled_sub_pixels},
        {"at_min_radius", s.irradiance.at_min_radius},
        {"at_max_radius", s.irradiance.at_max_radius},
        {"light_guide",
         {{"rays_per_record", s.guide.clusters ? c.guide_rays : 0u},
          {"clusters", s.guide.clusters},
          {"photons", s.guide.photons},
          {"seconds", s.guide.seconds}}},
        {"later_bounces",
         {{"method", s.bounces.count > 1 ? bounce_method_name(s.bounces.method) : "none"},
          {"photons_shot", s.photon_map.paths},
          {"photons_kept", s.photon_map.photons},
          {"radius", s.photon_map.radius},
          {"short_ray_paths_below", s.photon_map.radius * settings.short_ray_paths},
          {"min_support", settings.photon_min_support},
          {"seconds", s.photon_map.seconds},
          {"seconds_by_part",
           {{"shoot", s.photon_map.shoot_s},
            {"grids", s.photon_map.grids_s},
            {"estimates", s.photon_map.estimate_s}}}}},
        {"caustic_map",
         {{"photons_shot", s.caustics.paths},
          {"photons_kept", s.caustics.photons},
          {"radius", s.caustics.radius},
          {"seconds", s.caustics.seconds}}}};
    j["specular"] = {{"rough_pixels", s.primary.rough_pixels},
                     {"glossy_pixels", s.primary.glossy_pixels},
                     {"glossy_samples", s.glossy.samples},
                     {"glossy_adaptive", s.glossy.adaptive},
                     {"glossy_rounds", s.glossy.rounds},
                     {"glossy_mean_samples", s.glossy.mean_samples},
                     {"glossy_most_samples", s.glossy.most_samples},
                     {"glossy_refined_pixels", s.glossy.refined_pixels},
                     {"glossy_rays", s.glossy.rays},
                     {"glossy_reads_records", s.glossy.reads_records},
                     {"record_grid_seconds", s.glossy.record_grid_s},
                     {"seconds", s.glossy.seconds}};
    if (s.radiance.order)
      j["radiance_cache"] = {{"pixels", s.primary.hsh_pixels},
                             {"order", s.radiance.order},
                             {"captured_energy", s.radiance.captured_energy},
                             {"accuracy", s.radiance.accuracy},
                             {"records", s.radiance.records},
                             {"rays", s.radiance.rays},
                             {"filled_sub_pixels", s.radiance.filled_sub_pixels},
                             {"seconds",
                              {{"lobe_table", s.radiance.lobe_table_s},
                               {"records", s.radiance.records_s},
                               {"placement", s.radiance.placement_s},
                               {"splat", s.radiance.splat_s}}}};
  }
  if (s.gi == GiMethod::path) j["path"] = {{"samples", s.path.samples}, {"stratified", settings.path.stratified}};
  return j;
}

}  // namespace

int run_render(const RenderOptions& options) {
  set_progress_lines(options.progress_lines);
  check_request(options.settings);  // every range, before the scene is read
  check_cache_files(options);
  if (options.outputs.empty()) throw Error("render: give at least one output with -o OUT.exr or -o OUT.png");
  for (const std::string& out : options.outputs) {
    if (!is_output_format(out)) throw Error(out + ": unknown output format (use " + output_formats() + ")");
    check_writable_destination(out);
  }
  if (!options.json_path.empty()) check_writable_destination(options.json_path);
  // Loaded before the scene, so that a missing library stops the run before any work and with no file written.
  std::unique_ptr<Denoiser> denoiser = options.denoise ? Denoiser::load() : nullptr;
  Scene scene = load_scene(options);  // the job's scene (sequence/render_job.h)
  DeviceInfo device = select_device(options.device);
  log_info("device: " + device.name + " (" + device.platform_name + ")");
  GpuContext gpu(device);
  gpu.set_memory_budget(options.limits.device_memory_bytes);
  RenderSettings settings = options.settings;
  settings.color_only = outputs_need_only_color(options.outputs) && !denoiser;  // it reads albedo and normal
  RenderedImage image;
  std::string earlier;  // --resume: the .exr output an earlier run wrote
  for (const std::string& out : options.outputs)
    if (earlier.empty() && lower_extension(out) == ".exr") earlier = out;
  if (options.resume && earlier.empty()) throw Error("--resume needs an .exr output to continue");
  if (options.resume && std::filesystem::exists(earlier)) {
    if (!resume_reference(gpu, scene, options, earlier, image)) {
      std::printf("%s already has %u or more samples per pixel\n", earlier.c_str(), options.settings.path.samples);
      return 0;
    }
  } else if (!options.cache_in.empty() || !options.cache_out.empty()) {
    settings.keep_records = true;
    Renderer renderer(gpu, scene, settings.forced_switches);
    const FramePlan plan = renderer.plan(settings);
    if (!options.cache_in.empty()) load_cache_file(gpu, renderer, scene, plan, options.cache_in);
    image = renderer.render(plan);
    if (!options.cache_out.empty()) save_cache_file(gpu, renderer, scene, plan, options.cache_out);
  } else {
    image = render(gpu, scene, settings);
  }
  const ScenePlan plan = plan_scene(scene);
  if (denoiser) {
    DenoiseChoice choice;
    choice.direct_sampled = plan.emissive_triangles > 0 || !plan.environment.empty();
    denoise_frame(*denoiser, choice, image);
    image.stats.total_s += image.stats.denoise.seconds;
  }
  ExrAttributes attributes = render_attributes(scene, image, options.settings);
  if (denoiser) attributes["rcsplat:denoised"] = image.stats.denoise.layers.empty() ? "nothing sampled per pixel"
                                                                                     : image.stats.denoise.layers;
  for (const std::string& out : options.outputs) write_render(out, image, options.exposure, attributes);
  report_progress(1.0);
  print_summary(scene, plan, image, options.settings, options.outputs);
  if (options.settings.gi != GiMethod::path)
    std::printf("quality      %s\n", quality_summary(options.quality, options.settings).c_str());
  if (!options.json_path.empty()) {
    nlohmann::json j = summary_json(scene, plan, image, options.settings, options.outputs);
    if (options.settings.gi != GiMethod::path) j["quality"] = options.quality;
    write_text_file(options.json_path, j.dump(2) + "\n");
  }
  return 0;
}

Command add_render_command(CLI::App& app, const HelpGroups& groups) {
  struct State {
    RenderOptions options;
    CameraFlags camera;
    EnvironmentFlags environment;
    RenderMethodFlags method;
  };
  auto s = std::make_shared<State>();
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF scene (default: the built-in Cornell box)");
  add_frame_options(cmd, s->options, s->options.json_path, s->options.progress_lines, s->camera, s->environment,
                    groups);
  cmd->add_flag("--denoise", s->options.denoise,
                "Denoise the light each pixel samples itself (area and environment direct light, sharp glossy "
                "lobes; path tracing: the whole image) with Intel Open Image Denoise, and compose it with the "
                "cache's indirect light, which stays as it is; the EXR keeps the noisy layers too (noisy, "
                "noisy_direct, noisy_glossy, noisy_indirect). Needs the library: bash scripts/install-oidn.sh");
  if (!groups.help_all) cmd->footer("--help-all also lists the experiment options.");
  s->method.add(cmd, s->options, s->options.quality, groups);
  return {cmd, [s, cmd] {
            s->camera.apply(s->options.settings);
            s->environment.apply(s->options.environment);
            s->method.apply(cmd, s->options, s->options.quality);
            return run_render(s->options);
          }};
}

}  // namespace rcsplat
