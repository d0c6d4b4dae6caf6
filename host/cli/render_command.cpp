#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "cli/commands.h"
#include "image/image_io.h"
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
  print_scene_plan(plan, s.bvh_depth);  // what `rcsplat info` prints
  std::printf("device       %s\n", s.device.c_str());
  std::printf("image        %d x %d, %u light samples per pixel, indirect light: %s, %u bounce%s\n", image.width,
              image.height, s.light_samples, gi_method_name(s.gi), s.bounces, s.bounces == 1 ? "" : "s");
  if (s.bounces_chosen)
    std::printf("bounces      %u chosen from the scene: each reflection keeps %.0f%% of the light it receives (photons "
                "measured it), so the bounces left out carry at most %.0f%% of the indirect light (--bounces)\n",
                s.bounces, 100.0 * s.kept_per_bounce, 100.0 * kMissingIndirectShare);
  if (s.gi == GiMethod::path && settings.path.pixel_area)
    std::printf("pixels       %u primary sample%s each, at random points of the cells of a %ux%u grid over the pixel "
                "(%u rounds of the frame, averaged: the pixel's area integral)\n",
                s.pixel_samples, s.pixel_samples == 1 ? "" : "s", pixel_sample_side(s.pixel_samples),
                pixel_sample_side(s.pixel_samples), s.pixel_samples);
  else if (s.pixel_samples > 1 && s.gi != GiMethod::splat && s.gi != GiMethod::octree)
    std::printf("pixels       %u primary samples each (a %ux%u sub-pixel grid, rendered as a %d x %d frame and "
                "averaged)\n",
                s.pixel_samples, pixel_sample_side(s.pixel_samples), pixel_sample_side(s.pixel_samples),
                image.width * int(pixel_sample_side(s.pixel_samples)),
                image.height * int(pixel_sample_side(s.pixel_samples)));
  else if (s.pixel_samples > 1)
    std::printf("pixels       %u primary samples each (a %ux%u sub-pixel grid, rendered as a %d x %d frame and "
                "averaged); record reach and placement spacing are in output pixels (spacings below are in sub-pixels), "
                "and placement stops one output pixel apart, so the records are those one sample places; %llu sub-pixels "
                "no record reached (edges) took the best-weighted record near them\n",
                s.pixel_samples, pixel_sample_side(s.pixel_samples), pixel_sample_side(s.pixel_samples),
                image.width * int(pixel_sample_side(s.pixel_samples)),
                image.height * int(pixel_sample_side(s.pixel_samples)), (unsigned long long)s.filled_sub_pixels);
  std::printf("BVH          %zu nodes, %zu triangle blocks, depth %d\n", s.bvh_nodes, s.bvh_blocks, s.bvh_depth);
  std::printf("rays         %llu primary, %llu shadow\n", (unsigned long long)s.primary_rays,
              (unsigned long long)s.shadow_rays);
  std::printf("time         BVH build %.3f s, upload %.3f s, kernel build %.3f s\n", s.bvh_build_s, s.upload_s, s.program_s);
  std::printf("             G-buffer %.3f s, direct light %.3f s (%.2f Mrays/s)\n", s.gbuffer_s, s.direct_s,
              mrays_per_second(s.primary_rays + s.shadow_rays, s.gbuffer_s + s.direct_s));
  if (s.gi == GiMethod::splat || s.gi == GiMethod::octree) {
    const CacheSettings& c = settings.cache;
    std::printf("cache        a = %g, %ux%u rays per record", c.accuracy, c.theta_strata, c.phi_strata);
    if (c.fine_theta_strata) std::printf(" (%ux%u at spacing 1)", c.fine_theta_strata, c.fine_phi_strata);
    std::printf(", record spacing %g..%g pixels, ", c.min_reach_pixels, c.max_reach_pixels);
    if (c.adaptive_error > 0.0f)
      std::printf("adaptive rays (%ux%u first, all where the error score is above %g: %llu records), ",
                  c.theta_strata / 2, c.phi_strata / 2, c.adaptive_error, (unsigned long long)s.adaptive_records);
    if (c.hessian_error > 0.0f) std::printf("radii from the occlusion Hessian (error budget %g)\n", c.hessian_error);
    else std::printf("radii from Ward's split sphere\n");
    if (s.photon_map_photons)
      std::printf("photon map   bounces 2..%u at the records' hits: %llu landings after a reflection, from %llu photons shot; radius %.4g, record rays shorter than %.4g continue a bounce (%.3f s)\n",
                  s.bounces, (unsigned long long)s.photon_map_photons, (unsigned long long)s.photon_map_paths,
                  s.photon_map_radius, s.photon_map_radius * settings.short_ray_paths, s.photon_map_s);
    else if (s.bounces > 1)
      std::printf("bounces      2..%u at the records' hits by path continuation\n", s.bounces);
    if (s.guide_clusters)
      std::printf("light guide  %u rays per record at %u bright places found by %llu photons (%.3f s)\n", c.guide_rays,
                  s.guide_clusters, (unsigned long long)s.guide_photons, s.guide_s);
    else
      std::printf("light guide  none (%s)\n", c.guide_rays ? "no light with power" : "--guide-rays 0");
    std::printf("records      %llu:", (unsigned long long)s.records);
    for (const PlacementLevel& l : s.levels) std::printf(" %u at spacing %d;", l.records, l.spacing_pixels);
    std::printf(" %llu pixels left uncovered\n", (unsigned long long)s.uncovered_pixels);
    std::printf("             reach at the minimum spacing: %.1f%%, at the maximum: %.1f%%\n",
                100.0 * double(s.records_at_min_radius) / double(std::max<uint64_t>(s.records, 1)),
                100.0 * double(s.records_at_max_radius) / double(std::max<uint64_t>(s.records, 1)));
    std::printf("             %llu rays (%.2f Mrays/s)\n", (unsigned long long)s.record_rays,
                mrays_per_second(s.record_rays, s.records_s));
    std::printf("time         records %.3f s, placement %.3f s, splat %.3f s, resolve %.3f s\n", s.records_s,
                s.placement_s, s.splat_s, s.resolve_s);
    if (s.rough_pixels || s.glossy_pixels || s.glossy_rays)
      std::printf("specular     %llu rough pixels from the irradiance; %llu glossy pixels, %u lobe samples each; per "
                  "pixel (lobes, and the light guide's share of radiance-cached pixels): %llu rays, %.3f s (%.2f "
                  "Mrays/s)\n",
                  (unsigned long long)s.rough_pixels, (unsigned long long)s.glossy_pixels, s.glossy_samples,
                  (unsigned long long)s.glossy_rays, s.glossy_s, mrays_per_second(s.glossy_rays, s.glossy_s));
    if (s.hsh_order)
      std::printf("radiance     %llu radiance-cached pixels: HSH order %u (%u coefficients a channel, holds %.0f%% of the "
                  "sharpest cached lobe), a = %g, %llu records, %llu rays (%.2f Mrays/s), %llu sub-pixels filled\n"
                  "time         lobe table %.3f s, records %.3f s, placement %.3f s, splat %.3f s\n",
                  (unsigned long long)s.hsh_pixels, s.hsh_order, s.hsh_order * s.hsh_order,
                  100.0 * s.hsh_captured_energy, double(s.radiance_accuracy), (unsigned long long)s.radiance_records,
                  (unsigned long long)s.radiance_record_rays,
                  mrays_per_second(s.radiance_record_rays, s.radiance_records_s),
                  (unsigned long long)s.radiance_filled_sub_pixels, s.hsh_table_s, s.radiance_records_s,
                  s.radiance_placement_s, s.radiance_splat_s);
  }
  if (s.gi == GiMethod::path) {
    std::printf("path         %u samples per pixel%s, %llu rays, %.3f s (%.2f Mrays/s)\n", s.path_samples,
                settings.path.stratified ? " (stratified)" : "", (unsigned long long)s.path_rays, s.path_s,
                mrays_per_second(s.path_rays, s.path_s));
  }
  print_memory(s.device_memory);
  std::printf("total        %.3f s (on the host between passes: bounce probe %.3f s, image layers %.3f s)\n",
              s.total_s, s.probe_s, s.layers_s);
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
      {"scene_plan", scene_plan_json(plan, s.bvh_depth)},
      {"scene", scene.source}, {"device", s.device}, {"width", image.width}, {"height", image.height},
      {"gi", gi_method_name(s.gi)}, {"bounces", s.bounces}, {"bounces_chosen", s.bounces_chosen},
      {"kept_per_bounce", s.kept_per_bounce}, {"light_samples", s.light_samples},
      {"pixel_samples", s.pixel_samples},
      {"pixel_points", pixel_points_name(settings)},
      {"triangles", s.triangles},
      {"bvh", {{"nodes", s.bvh_nodes}, {"blocks", s.bvh_blocks}, {"depth", s.bvh_depth}}},
      {"rays", {{"primary", s.primary_rays}, {"shadow", s.shadow_rays}, {"records", s.record_rays},
                {"path", s.path_rays}}},
      {"seconds", {{"bvh_build", s.bvh_build_s}, {"upload", s.upload_s}, {"kernel_build", s.program_s},
                   {"gbuffer", s.gbuffer_s}, {"direct", s.direct_s}, {"records", s.records_s},
                   {"placement", s.placement_s}, {"splat", s.splat_s}, {"resolve", s.resolve_s},
                   {"path", s.path_s}, {"photon_map", s.photon_map_s}, {"light_guide", s.guide_s},
                   {"glossy", s.glossy_s}, {"bounce_probe", s.probe_s}, {"layers", s.layers_s},
                   {"total", s.total_s}}},
      {"memory", memory_json(s.device_memory)},
      {"outputs", outputs}, {"not_simulated", scene.unsupported}, {"nonfinite_values", nonfinite_values(image)},
      {"materials", {{"lambertian", s.lambertian_materials}, {"rough", s.rough_materials},
                     {"radiance_cached", s.hsh_materials}, {"glossy", s.glossy_materials},
                     {"brdf_compiled", s.specular_brdf}, {"hsh_compiled", s.hsh_materials > 0},
                     {"radiance_cached_min_roughness", HSH_MIN_ROUGHNESS}}}};
  if (s.gi == GiMethod::splat || s.gi == GiMethod::octree) {
    const CacheSettings& c = settings.cache;
    nlohmann::json levels = nlohmann::json::array();
    for (const PlacementLevel& l : s.levels) levels.push_back({{"spacing", l.spacing_pixels}, {"records", l.records}});
    j["cache"] = {{"accuracy", c.accuracy}, {"hemisphere", {c.theta_strata, c.phi_strata}},
                  {"fine_hemisphere", {c.fine_theta_strata, c.fine_phi_strata}},
                  {"spacing", {c.min_reach_pixels, c.max_reach_pixels}},
                  {"radius_rule", c.hessian_error > 0.0f ? "occlusion_hessian" : "split_sphere"},
                  {"hessian_error", c.hessian_error},
                  {"adaptive_rays", {{"error", c.adaptive_error}, {"records_traced_again", s.adaptive_records}}},
                  {"records", s.records}, {"levels", levels},
                  {"uncovered_pixels", s.uncovered_pixels}, {"filled_sub_pixels", s.filled_sub_pixels}, {"at_min_radius", s.records_at_min_radius},
                  {"at_max_radius", s.records_at_max_radius},
                  {"light_guide", {{"rays_per_record", s.guide_clusters ? c.guide_rays : 0u},
                                   {"clusters", s.guide_clusters}, {"photons", s.guide_photons},
                                   {"seconds", s.guide_s}}},
                  {"later_bounces",
                   {{"method", s.bounces > 1 ? bounce_method_name(s.bounce_method) : "none"},
                    {"photons_shot", s.photon_map_paths},
                    {"photons_kept", s.photon_map_photons}, {"radius", s.photon_map_radius},
                    {"short_ray_paths_below", s.photon_map_radius * settings.short_ray_paths},
                    {"seconds", s.photon_map_s},
                    {"seconds_by_part",
                     {{"shoot", s.photon_map_shoot_s}, {"grids", s.photon_map_grids_s},
                      {"estimates", s.photon_map_estimate_s}}}}}};
    j["specular"] = {{"rough_pixels", s.rough_pixels}, {"glossy_pixels", s.glossy_pixels},
                     {"glossy_samples", s.glossy_samples}, {"glossy_rays", s.glossy_rays}, {"seconds", s.glossy_s}};
    if (s.hsh_order)
      j["radiance_cache"] = {{"pixels", s.hsh_pixels}, {"order", s.hsh_order}, {"captured_energy", s.hsh_captured_energy},
                             {"accuracy", s.radiance_accuracy}, {"records", s.radiance_records},
                             {"rays", s.radiance_record_rays}, {"filled_sub_pixels", s.radiance_filled_sub_pixels},
                             {"seconds", {{"lobe_table", s.hsh_table_s}, {"records", s.radiance_records_s},
                                          {"placement", s.radiance_placement_s}, {"splat", s.radiance_splat_s}}}};
  }
  if (s.gi == GiMethod::path) j["path"] = {{"samples", s.path_samples}, {"stratified", settings.path.stratified}};
  return j;
}

}  // namespace

int run_render(const RenderOptions& options) {
  check_request(options.settings);  // every range, before the scene is read
  if (options.outputs.empty()) throw Error("render: give at least one output with -o OUT.exr or -o OUT.png");
  for (const std::string& out : options.outputs) {
    if (!is_output_format(out)) throw Error(out + ": unknown output format (use " + output_formats() + ")");
    check_writable_destination(out);
  }
  if (!options.json_path.empty()) check_writable_destination(options.json_path);
  Scene scene =
      load_scene(options.scene_path, options.settings.camera, options.settings.camera_overrides, options.environment,
                 options.limits);
  DeviceInfo device = select_device(options.device);
  log_info("device: " + device.name + " (" + device.platform_name + ")");
  GpuContext gpu(device);
  gpu.set_memory_budget(options.limits.device_memory_bytes);
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
  } else {
    image = render(gpu, scene, options.settings);
  }
  const ExrAttributes attributes = render_attributes(scene, image, options.settings);
  for (const std::string& out : options.outputs) write_render(out, image, options.exposure, attributes);
  const ScenePlan plan = plan_scene(scene);
  print_summary(scene, plan, image, options.settings, options.outputs);
  if (options.settings.gi != GiMethod::path) std::printf("quality      %s\n", quality_summary(options.quality, options.settings).c_str());
  if (!options.json_path.empty()) {
    nlohmann::json j = summary_json(scene, plan, image, options.settings, options.outputs);
    if (options.settings.gi != GiMethod::path) j["quality"] = options.quality;
    write_text_file(options.json_path, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace rcsplat
