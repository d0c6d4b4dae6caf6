#include "sequence/render_job.h"

#include <cstdio>

#include "render/camera.h"
#include "render/kept_records.h"
#include "render/pixel_samples.h"
#include "scene/cornell_box.h"
#include "sequence/cache_file.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {

Scene load_scene(const std::string& path, int camera, const CameraOverrides& overrides,
                 const EnvironmentSettings& environment, const SceneLimits& limits, const ScenePose& pose) {
  Scene scene = path.empty() ? make_cornell_box() : load_gltf(path, limits, pose);
  scene.environment = make_environment(environment);
  scene.glass_light = environment.glass;
  add_view_defaults(scene, camera, overrides);
  return scene;
}

std::string light_through_glass_name(const GlassLight& g) {
  return g.caustics ? "caustics (" + std::to_string(g.photons) + " photon paths)" : "straight";
}

ExrAttributes render_attributes(const Scene& scene, const RenderedImage& image, const RenderSettings& settings) {
  // The view, so that another renderer can render the same picture (benchmarks/mitsuba_peer.py reads it).
  const SceneCamera cam = choose_camera(scene, settings.camera, settings.camera_overrides);
  char view[360];
  std::snprintf(view, sizeof view,
                "%s eye %.9g,%.9g,%.9g target %.9g,%.9g,%.9g up %.9g,%.9g,%.9g yfov_degrees %.9g ymag %.9g",
                cam.orthographic ? "orthographic" : "perspective", cam.eye.x, cam.eye.y, cam.eye.z, cam.target.x,
                cam.target.y, cam.target.z, cam.up.x, cam.up.y, cam.up.z, double(glm::degrees(cam.yfov)),
                double(cam.ymag));
  // What a later --resume needs to know, what compare checks, and what anyone reading the file may want.
  return {{"rcsplat:scene", scene.source},
          {"rcsplat:camera", view},
          {"rcsplat:gi", gi_method_name(image.stats.gi)},
          {"rcsplat:path_samples", std::to_string(image.stats.path.samples)},
          {"rcsplat:light_samples", std::to_string(image.stats.primary.light_samples)},
          {"rcsplat:seed", std::to_string(settings.seed)},
          {"rcsplat:stratified", settings.path.stratified ? "1" : "0"},
          {"rcsplat:bounces", std::to_string(image.stats.bounces.count)},
          {"rcsplat:bounce_method", bounce_method_name(image.stats.bounces.method)},
          {"rcsplat:environment", scene.environment.describe()},
          {"rcsplat:light_through_glass", light_through_glass_name(scene.glass_light)},
          {"rcsplat:pixel_samples", std::to_string(image.stats.primary.pixel_samples)},
          {"rcsplat:pixel_points", pixel_points_name(settings)}};
}

Scene load_scene(const RenderJob& job, const ScenePose& pose) {
  return load_scene(job.scene_path, job.settings.camera, job.settings.camera_overrides, job.environment, job.limits,
                    pose);
}

void check_cache_files(const RenderJob& o) {
  if ((!o.cache_in.empty() || !o.cache_out.empty()) && o.settings.gi != GiMethod::splat)
    throw Error("--cache-in and --cache-out: only the splat keeps records (--gi splat)");
  if (!o.cache_out.empty()) check_writable_destination(o.cache_out);
}

namespace {
CacheFileIdentity cache_identity(const GpuContext& gpu, const Scene& scene, const FramePlan& plan) {
  return {scene_fingerprint(scene), settings_fingerprint(kept_records_key(plan.frame_settings())), gpu.device_info().name};
}
}  // namespace

void load_cache_file(const GpuContext& gpu, KeptCache& kept, const Scene& scene, const FramePlan& plan,
                     const std::string& path, int animation) {
  read_cache_file(path, cache_identity(gpu, scene, plan), kept_records_key(plan.frame_settings()), cache_file_limits(plan.frame_settings()),
                  kept);
  const int holds = kept.times.animation;
  if (holds != animation) {
    auto moved_by = [&](int a) {
      return a < 0 ? std::string("the scene standing still")
                   : "the scene moved by animations[" + std::to_string(a) + "]" +
                         (size_t(a) < scene.animation_names.size() ? " '" + scene.animation_names[size_t(a)] + "'" : "");
    };
    throw Error(path + ": its records hold " + moved_by(holds) + ", and this render draws " + moved_by(animation) +
                (animation < 0 ? std::string(" (`render` draws a scene as it stands; `animate` plays its animation)")
                               : std::string()));
  }
  log_info(path + ": " + std::to_string(kept.irradiance.size()) + " irradiance records, " +
           std::to_string(kept.radiance.size()) + " radiance records, " + std::to_string(kept.light.photons.size()) +
           " photons, " + std::to_string(kept.light.caustic_photons.size()) + " caustic photons and " +
           std::to_string(kept.light.guide_clusters.size()) + " light guide clusters read");
}

void load_cache_file(const GpuContext& gpu, Renderer& renderer, const Scene& scene, const FramePlan& plan,
                     const std::string& path, int animation) {
  load_cache_file(gpu, renderer.kept_records(), scene, plan, path, animation);
}

void save_cache_file(const GpuContext& gpu, const KeptCache& kept, const Scene& scene, const FramePlan& plan,
                     const std::string& path) {
  write_cache_file(path, kept, cache_identity(gpu, scene, plan));
}

void save_cache_file(const GpuContext& gpu, Renderer& renderer, const Scene& scene, const FramePlan& plan,
                     const std::string& path) {
  save_cache_file(gpu, renderer.kept_records(), scene, plan, path);
}

}  // namespace rcsplat
