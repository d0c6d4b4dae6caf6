#include "render/renderer.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bvh/bvh8.h"
#include "cl/device_scene.h"
#include "kernels/hsh.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "render/indirect.h"
#include "render/bounce_choice.h"
#include "render/pixel_samples.h"
#include "scene/scene_frame.h"
#include "util/byte_size.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {

const char* gi_method_name(GiMethod method) {
  switch (method) {
    case GiMethod::none: return "none";
    case GiMethod::splat: return "splat";
    case GiMethod::octree: return "octree";
    case GiMethod::path: return "path";
  }
  return "?";
}

const char* bounce_method_name(BounceMethod method) {
  switch (method) {
    case BounceMethod::automatic: return "auto";
    case BounceMethod::path: return "path";
    case BounceMethod::photons: return "photons";
  }
  return "?";
}

namespace {

// Refuses, before any work, a frame that cannot fit: the per-pixel buffers every method allocates on the device
// (G-buffer, direct light, composition, placement flags, splat sums) and the layers the host keeps and writes. A
// lower bound: records and scene data come on top. Without it a huge --width would end in a failed allocation deep in
// a pass, or on the host in the kernel's out-of-memory killer.
void check_frame_fits(int width, int height, const DeviceInfo& device) {
  const double pixels = double(width) * double(height);
  const double device_bytes = pixels * (sizeof(GBufferSample) + 16 + 32 + 5 + 52);
  const double host_bytes = pixels * (sizeof(GBufferSample) + 16 + 116 + 104);
  const double host_memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  auto gib = [](double bytes) { return byte_size(bytes, "GiB"); };
  const std::string frame = std::to_string(width) + "x" + std::to_string(height);
  if (device.global_memory && device_bytes > double(device.global_memory))
    throw Error("out of device memory: a " + frame + " frame needs at least " + gib(device_bytes) + " of device memory; '" +
                device.name + "' has " + gib(double(device.global_memory)) + " (--width, --height)");
  if (host_memory > 0.0 && host_bytes > host_memory)
    throw Error("out of host memory: a " + frame + " frame needs at least " + gib(host_bytes) +
                " of host memory; this machine has " + gib(host_memory) + " (--width, --height)");
}

}  // namespace

RenderedImage render_single_sample(GpuContext& gpu, const Scene& scene, const RenderSettings& requested) {
  RenderSettings settings = requested;  // with the bounces and their method chosen, below
  if (settings.gi == GiMethod::splat || settings.gi == GiMethod::octree) validate_cache_settings(settings.cache);
  // The command line refuses it too; a caller of the library gets the same words before any work.
  if (settings.bounces > kMaxBounces)
    throw Error("--bounces must be between 1 and " + std::to_string(kMaxBounces) + " (0: chosen from the scene)");
  if (settings.bounce_method == BounceMethod::photons && settings.bounces != 1 && settings.gi != GiMethod::path &&
      settings.gi != GiMethod::none && scene.environment.present())
    throw Error("--bounce-method photons: the photons come from the lights and an environment's peak, not from its "
                "gathered part, so a sky's later bounces would be lost; use --bounce-method path with --sky or "
                "--environment");
  if (settings.hsh_order > HSH_MAX_ORDER)
    throw Error("--hsh-order must be between 1 and " + std::to_string(HSH_MAX_ORDER) + " (0: chosen from the roughness)");
  auto start = Clock::now();
  gpu.restart_memory_peak();
  RenderedImage img;
  RenderStats& st = img.stats;
  st.device = gpu.device_info().name;
  st.triangles = scene.triangle_count();
  st.gi = settings.gi;

  SceneCamera cam = choose_camera(scene, settings.camera, settings.camera_overrides);
  img.width = settings.width;
  img.height = settings.height;
  resolve_resolution(cam, img.width, img.height);
  check_frame_fits(img.width, img.height, gpu.device_info());
  scene.check_extent();
  // The device traces and shades in coordinates centred on the scene and scaled to it (scene/scene_frame.h); the
  // position and depth layers and the records go back to world units below.
  const SceneFrame scene_frame = SceneFrame::fitted(scene);
  CameraParams params = camera_params(scene_frame.device_camera(cam), img.width, img.height);
  unsigned strata = settings.light_samples ? unsigned(std::ceil(std::sqrt(double(settings.light_samples)))) : 0;
  st.light_samples = strata * strata;

  log_info("building the BVH over " + std::to_string(st.triangles) + " triangles");
  Bvh8 bvh = build_bvh8(scene_frame.device_positions(scene));
  st.bvh_build_s = bvh.build_seconds;
  st.bvh_nodes = bvh.nodes.size();
  st.bvh_blocks = bvh.blocks.size();
  st.bvh_depth = bvh.depth;

  auto t = Clock::now();
  DeviceScene device_scene(gpu, scene, bvh, settings.forced_switches, scene_frame);
  st.lambertian_materials = device_scene.lobe_counts()[LOBE_NONE];
  st.rough_materials = device_scene.lobe_counts()[LOBE_ROUGH];
  st.glossy_materials = device_scene.lobe_counts()[LOBE_GLOSSY];
  st.hsh_materials = device_scene.lobe_counts()[LOBE_HSH];
  st.specular_brdf = device_scene.has_specular_brdf();
  st.upload_s = seconds_since(t);
  const BounceChoice bounce_choice = choose_bounces(gpu, scene, device_scene, settings);
  settings.bounces = bounce_choice.bounces;
  settings.bounce_method = bounce_choice.method;
  st.bounces = bounce_choice.bounces;
  st.bounce_method = bounce_choice.method;
  st.bounces_chosen = bounce_choice.bounces_chosen;
  st.kept_per_bounce = bounce_choice.kept_per_bounce;
  double program_before = gpu.program_seconds();
  log_info("compiling kernels for " + st.device);
  GBufferPass gbuffer(gpu, device_scene);
  DirectPass direct(gpu, device_scene);
  st.program_s = gpu.program_seconds() - program_before;

  t = Clock::now();
  gbuffer.run(params);
  st.gbuffer_s = seconds_since(t);
  t = Clock::now();
  direct.run(gbuffer.view(), strata, settings.seed);
  st.direct_s = seconds_since(t);

  std::vector<GBufferSample> g = gbuffer.download();
  std::vector<float> d = direct.download_rgba();
  size_t pixels = g.size();
  img.color.resize(pixels * 3);
  img.direct.resize(pixels * 3);
  img.emission.resize(pixels * 3);
  img.albedo.resize(pixels * 3);
  img.normal.resize(pixels * 3);
  img.position.resize(pixels * 3);
  img.depth.resize(pixels);
  img.triangle.resize(pixels);
  st.primary_rays = pixels;
  for (size_t i = 0; i < pixels; ++i) {
    const GBufferSample& s = g[i];
    img.triangle[i] = s.triangle;
    if (s.triangle >= 0) {
      st.rough_pixels += s.lobe == LOBE_ROUGH;
      st.glossy_pixels += s.lobe == LOBE_GLOSSY;
      st.hsh_pixels += s.lobe == LOBE_HSH;
    }
    img.depth[i] = s.triangle >= 0 ? scene_frame.length_to_world(s.depth) : 0.0f;
    const glm::vec3 world = s.triangle >= 0 ? scene_frame.to_world(glm::vec3(s.position[0], s.position[1], s.position[2]))
                                            : glm::vec3(0.0f);
    st.shadow_rays += uint64_t(d[4 * i + 3]);
    for (int c = 0; c < 3; ++c) {
      img.direct[3 * i + c] = d[4 * i + c];
      img.emission[3 * i + c] = s.emission[c];
      img.albedo[3 * i + c] = s.albedo[c];
      img.normal[3 * i + c] = s.normal[c];
      img.position[3 * i + c] = world[c];
      img.color[3 * i + c] = s.emission[c] + d[4 * i + c];
    }
  }

  IndirectFrame frame{gpu, scene, device_scene, gbuffer, direct, settings, img};
  switch (settings.gi) {
    case GiMethod::none: break;
    case GiMethod::splat: splat_indirect(frame); break;
    case GiMethod::octree: octree_indirect(frame); break;
    case GiMethod::path: path_traced_indirect(frame); break;
  }
  for (CacheRecord& r : img.records) r = scene_frame.world_record(r);
  st.total_s = seconds_since(start);
  st.device_memory = gpu.memory_use();
  return img;
}

}  // namespace rcsplat
