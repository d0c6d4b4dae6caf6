// `rcsplat info SCENE`: what the scene contains and what rcsplat will simulate for it (scene/scene_plan.h), the same
// lines the render summary prints, and the kernel switches a render compiles. The bounce count a render chooses comes
// from a photon probe on an OpenCL device; without one, info says so and prints the rest.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bvh/bvh8.h"
#include "cl/device_bvh.h"
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "cli/command_line.h"
#include "cli/commands.h"
#include "util/atomic_file.h"
#include "render/bounce_choice.h"
#include "render/renderer.h"
#include "scene/scene_frame.h"
#include "util/error.h"

namespace rcsplat {

void print_scene_plan(const ScenePlan& plan, int bvh_depth) {
  std::printf("triangles    %zu, %zu of them emissive\n", plan.triangles, plan.emissive_triangles);
  std::printf("materials    %zu: %u Lambertian, %u rough, %u radiance-cached, %u glossy\n", plan.materials.size(),
              plan.lobe_counts[LOBE_NONE], plan.lobe_counts[LOBE_ROUGH], plan.lobe_counts[LOBE_HSH],
              plan.lobe_counts[LOBE_GLOSSY]);
  for (const MaterialPlan& m : plan.materials)
    std::printf("  %-24s %s (roughness %.2f, metallic %.2f%s%s%s%s%s%s%s%s): %s\n", m.name.c_str(), lobe_name(m.lobe),
                double(m.roughness), double(m.metallic), m.emissive ? ", emissive" : "", m.textured ? ", textured" : "",
                m.normal_mapped ? ", normal map" : "", m.emissive_textured ? ", emissive texture" : "",
                m.clearcoat ? ", clearcoat" : "", m.sheen ? ", sheen" : "", m.specular_colour ? ", specular colour" : "",
                !m.glass ? "" : m.thin_walled ? ", thin-walled glass" : ", glass with a volume", material_treatment(m));
  std::printf("textures     %zu%s%s%s%s\n", plan.textures,
              plan.textures ? " (filtered by each ray's footprint through mip chains where the sampler allows)" : "",
              plan.vertex_colors ? ", vertex colours" : "",
              plan.alpha_mask ? ", alpha-masked cutouts" : "",
              plan.alpha_blend ? ", alpha-blended surfaces (hashed transparency: seen with probability alpha)" : "");
  if (plan.normal_mapped_materials)
    std::printf("normal maps  %u material(s): the mapped normal shades (direct light, BRDF, glossy and path); the cache "
                "weighs records by the interpolated normal and turns their irradiance to the mapped one by its rotation "
                "gradient\n", plan.normal_mapped_materials);
  if (plan.emissive_textured_materials)
    std::printf("emission     %u material(s) textured: seen and sampled at their texels, emitters chosen by their "
                "textured power\n", plan.emissive_textured_materials);
  if (plan.glass_materials)
    std::printf("glass        %u material(s): camera rays see through it (its colour and Fresnel) and see what it "
                "mirrors; every other ray reflects or passes by Fresnel; %s; records never sit on it\n",
                plan.glass_materials,
                plan.switches.at("HAS_GLASS_CAUSTICS") == "1"
                    ? "shadow rays pass thin-walled glass with its colour (exact) and stop at glass volumes, whose "
                      "light arrives focused, by the glass caustic map (--light-through-glass caustics)"
                    : "shadow rays pass it with its colour (thin-walled: exact; a volume: straight through, its "
                      "caustics not focused; --light-through-glass caustics focuses them)");
  if (plan.layered_materials)
    std::printf("layers       %u material(s) with clearcoat, sheen or specular colour: in direct light, at every hit, "
                "in the glossy pass and the path tracer; their lobes are sampled per pixel (glossy) or, where all are "
                "wide (rough), reflect the cached irradiance by their albedo; never radiance-cached\n",
                plan.layered_materials);
  std::printf("lights       %u point, %u spot, %u directional; %zu emissive triangles\n", plan.point_lights,
              plan.spot_lights, plan.directional_lights, plan.emissive_triangles);
  if (plan.environment.empty())
    std::printf("environment  none (no sky or environment light is simulated; rays that leave the scene see black)\n");
  else
    std::printf("environment  %s: seen by camera rays; %.1f%% of its power (texels above %g times its mean luminance) "
                "sampled by shadow rays, the rest gathered by the rays that leave the scene\n",
                plan.environment.c_str(), 100.0 * plan.environment_peak_fraction, kEnvironmentPeakOverMean);
  for (const std::string& line : plan.not_simulated) std::printf("not simulated %s\n", line.c_str());
  std::printf("compiles     BRDF code %s, HSH code %s, base-colour texture code %s, area-light sampling %s, punctual lights %s, "
              "environment %s, normal maps %s, emissive textures %s, glass %s, layers %s\n",
              plan.switches.at("HAS_SPECULAR_BRDF") == "1" ? "yes" : "no (every material is Lambertian)",
              plan.radiance_cache() ? "yes" : "no (no radiance-cached material)",
              plan.switches.at("HAS_TEXTURES") == "1" ? "yes" : "no (no base-colour texture)",
              plan.switches.at("HAS_EMITTERS") == "1" ? "yes" : "no (no emissive triangle)",
              plan.switches.at("HAS_PUNCTUAL_LIGHTS") == "1" ? "yes" : "no (no punctual light)",
              plan.switches.at("HAS_ENVIRONMENT") == "1" ? "yes" : "no (no --sky or --environment)",
              plan.switches.at("HAS_NORMAL_MAPS") == "1" ? "yes" : "no",
              plan.switches.at("HAS_EMISSIVE_TEXTURES") == "1" ? "yes" : "no",
              plan.switches.at("HAS_TRANSMISSION") == "1" ? "yes" : "no",
              plan.switches.at("HAS_LAYERS") == "1" ? "yes" : "no");
  std::printf("switches    ");
  for (const auto& [name, value] : scene_plan_switches(plan, bvh_depth))
    std::printf(" %s=%s", name.c_str(), value.c_str());
  std::printf("\n");
}

nlohmann::json scene_plan_json(const ScenePlan& plan, int bvh_depth) {
  nlohmann::json materials = nlohmann::json::array();
  for (const MaterialPlan& m : plan.materials)
    materials.push_back({{"name", m.name}, {"kind", lobe_name(m.lobe)}, {"roughness", m.roughness},
                         {"metallic", m.metallic}, {"emissive", m.emissive}, {"textured", m.textured},
                         {"normal_map", m.normal_mapped}, {"emissive_texture", m.emissive_textured},
                         {"glass", m.glass ? (m.thin_walled ? "thin-walled" : "volume") : "no"},
                         {"clearcoat", m.clearcoat}, {"sheen", m.sheen}, {"specular_colour", m.specular_colour},
                         {"shading", material_treatment(m)}});
  nlohmann::json environment = nullptr;
  if (!plan.environment.empty())
    environment = {{"description", plan.environment}, {"kind", plan.environment_map ? "map" : "uniform sky"},
                   {"width", plan.environment_width}, {"height", plan.environment_height},
                   {"intensity", plan.environment_intensity}, {"rotation_degrees", plan.environment_rotation_degrees},
                   {"mean_luminance", plan.environment_mean_luminance},
                   {"peak_fraction", plan.environment_peak_fraction},
                   {"peak_threshold_over_mean", kEnvironmentPeakOverMean}};
  return {{"triangles", plan.triangles},
          {"emissive_triangles", plan.emissive_triangles},
          {"materials", materials},
          {"materials_by_kind",
           {{"lambertian", plan.lobe_counts[LOBE_NONE]}, {"rough", plan.lobe_counts[LOBE_ROUGH]},
            {"radiance_cached", plan.lobe_counts[LOBE_HSH]}, {"glossy", plan.lobe_counts[LOBE_GLOSSY]}}},
          {"textures", plan.textures},
          {"vertex_colors", plan.vertex_colors},
          {"alpha_mask", plan.alpha_mask},
          {"alpha_blend", plan.alpha_blend},
          {"lights",
           {{"point", plan.point_lights}, {"spot", plan.spot_lights}, {"directional", plan.directional_lights}}},
          {"environment", environment},
          {"light_through_glass",
           plan.glass_materials == 0                          ? nlohmann::json(nullptr)
           : plan.switches.at("HAS_GLASS_CAUSTICS") == "1" ? "caustics"
                                                              : "straight"},
          {"not_simulated", plan.not_simulated},
          {"switches", scene_plan_switches(plan, bvh_depth)}};
}

namespace {

// The frame plan a render with the defaults makes (render/frame_plan.h): what --bounces and --bounce-method become
// when left out, the resolution, pixel samples and HSH order; or why info cannot tell: the probe's photons and the
// lobe table need an OpenCL device.
nlohmann::json plan_report(const Scene& scene, const std::string& device) {
  try {
    GpuContext gpu(select_device(device));
    Renderer renderer(gpu, scene);
    const FramePlan plan = renderer.plan(RenderSettings{});  // the library's defaults are the command line's
    const FrameBounces bounces = plan.bounces();
    const FrameImage image = plan.image();
    const FrameRadiance radiance = plan.radiance();
    std::printf("bounces      %u when --bounces is left out: each reflection keeps %.0f%% of the light it receives "
                "(photons measured it on %s), so the bounces left out carry at most %.0f%% of the indirect light; "
                "the cache takes the bounces after the first %s\n",
                bounces.count, 100.0 * bounces.kept_per_bounce, gpu.device_info().name.c_str(),
                100.0 * kMissingIndirectShare,
                bounces.count == 1 ? "(none)"
                : bounces.method == BounceMethod::photons ? "from a photon map"
                                                        : "by path continuation");
    std::printf("plan         render's defaults: %d x %d, %u pixel samples (%ux%u sub-pixels), %u light samples, "
                "accuracy %g, %ux%u rays a record",
                image.width, image.height, plan.settings.pixel_samples, image.side, image.side,
                plan.settings.light_samples, double(plan.settings.cache.accuracy), plan.settings.cache.theta_strata,
                plan.settings.cache.phi_strata);
    if (radiance.order)
      std::printf(", HSH order %u for the radiance-cached lobes (it holds %.0f%% of the sharpest; their records at "
                  "accuracy %g)",
                  radiance.order, 100.0 * radiance.captured_energy, double(radiance.accuracy));
    std::printf("\n");
    const std::vector<std::string> passes = frame_pass_names(plan.passes);
    std::string pass_list;
    for (const std::string& name : passes) pass_list += (pass_list.empty() ? "" : ", ") + name;
    std::printf("passes       render's defaults run: %s\n", pass_list.c_str());
    nlohmann::json report = {{"chosen", bounces.count}, {"kept_per_bounce", bounces.kept_per_bounce},
                             {"cache_method", bounce_method_name(bounces.method)}, {"device", gpu.device_info().name}};
    report["plan"] = {{"width", image.width}, {"height", image.height}, {"pixel_samples", plan.settings.pixel_samples},
                      {"light_samples", plan.settings.light_samples}, {"accuracy", plan.settings.cache.accuracy},
                      {"hsh_order", radiance.order}, {"radiance_accuracy", radiance.accuracy},
                      {"passes", passes}};
    return report;
  } catch (const std::exception& e) {  // no OpenCL platform or device, or one that cannot run the probe
    std::printf("bounces      chosen when rendering (the photon probe needs an OpenCL device: %s)\n", e.what());
    return {{"chosen", nullptr}, {"why_not", e.what()}};
  }
}

}  // namespace

int run_info(const InfoOptions& options) {
  const Scene scene = load_scene(options.scene_path, 0, {}, options.environment, options.limits);
  const ScenePlan plan = plan_scene(scene);
  // The BVH a render builds: over the scene in its fitted device frame (scene/scene_frame.h), so the depth matches.
  const SceneFrame frame = SceneFrame::fitted(scene);
  const Bvh8 bvh = build_bvh8(frame.device_positions(scene));
  std::printf("scene        %s\n", scene.source.c_str());
  print_scene_plan(plan, bvh.depth);
  const nlohmann::json bounces = plan_report(scene, options.device);
  if (!options.json_path.empty()) {
    nlohmann::json report = scene_plan_json(plan, bvh.depth);
    report["scene"] = scene.source;
    report["bounces"] = bounces;
    write_text_file(options.json_path, report.dump(2) + "\n");
  }
  return 0;
}

Command add_info_command(CLI::App& app, const HelpGroups&) {
  struct State {
    InfoOptions options;
    EnvironmentFlags environment;
  };
  auto s = std::make_shared<State>();
  CLI::App* cmd = app.add_subcommand(
      "info", "What a scene contains and what rcsplat will simulate for it, with the kernel switches it compiles");
  cmd->add_option("scene", s->options.scene_path, "glTF 2.0 scene (.gltf or .glb); default: the built-in Cornell box");
  cmd->add_option("--json", s->options.json_path, "Also write it as JSON");
  cmd->add_option("--device", s->options.device,
                  "OpenCL device for the bounce probe (the bounce count a render chooses); without one, info says so "
                  "and prints the rest");
  s->environment.add(cmd, s->options.environment);
  add_scene_limit_options(cmd, s->options.limits, false);
  return {cmd, [s] {
            s->environment.apply(s->options.environment);
            return run_info(s->options);
          }};
}

}  // namespace rcsplat
