#include "render/renderer.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "bvh/bvh8.h"
#include "cl/device_scene.h"
#include "kernels/counter_random.h"
#include "kernels/hsh.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/layer_pass.h"
#include "render/indirect.h"
#include "render/bounce_choice.h"
#include "render/pixel_samples.h"
#include "scene/scene_frame.h"
#include "util/byte_size.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"

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
// (G-buffer, direct light, composition, placement flags, splat sums, the gathered layers) and the layers the host
// keeps and writes (output pixels, side times fewer each way than the G-buffer's). A lower bound: records and scene
// data come on top. Without it a huge --width would end in a failed allocation deep in a pass, or on the host in the
// kernel's out-of-memory killer.
void check_frame_fits(int width, int height, unsigned side, const DeviceInfo& device) {
  const double pixels = double(width) * double(height), out_pixels = pixels / double(side * side);
  const double device_bytes =
      pixels * (sizeof(GBufferSample) + 16 + 32 + 5 + 52) + out_pixels * 16;
  const double host_bytes = out_pixels * (sizeof(PixelSurface) + 16 + 116 + 104);
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

// Primary visibility through `camera`, direct light (strata x strata samples a sub-pixel) and the indirect light of
// one frame, into img (output resolution, layers.side() times smaller than the G-buffer; its statistics already hold
// the setup's); progress: the path tracer's, shared by rounds.
void shade_frame(GpuContext& gpu, const Scene& scene, const DeviceScene& device_scene, const SceneFrame& scene_frame,
                 GBufferPass& gbuffer, DirectPass& direct, LayerPass& layers, const CameraParams& camera,
                 unsigned strata, const RenderSettings& settings, RenderedImage& img, Progress* progress = nullptr,
                 size_t progress_done_before = 0) {
  RenderStats& st = img.stats;
  auto t = Clock::now();
  gbuffer.run(camera);
  st.gbuffer_s = seconds_since(t);
  t = Clock::now();
  direct.run(gbuffer.view(), strata, settings.seed);
  st.direct_s = seconds_since(t);

  t = Clock::now();
  const size_t pixels = layers.pixel_count();
  img.color.resize(pixels * 3);
  img.direct.resize(pixels * 3);
  img.emission.resize(pixels * 3);
  img.albedo.resize(pixels * 3);
  img.normal.resize(pixels * 3);
  img.position.resize(pixels * 3);
  img.depth.resize(pixels);
  img.triangle.resize(pixels);
  st.primary_rays = gbuffer.view().pixel_count();
  std::atomic<uint64_t> rough{0}, glossy{0}, hsh{0}, shadow_rays{0};
  layers.surface(gbuffer.view(), direct.radiance(), [&](size_t first, const PixelSurface* piece, size_t count) {
    parallel_ranges(count, [&](size_t begin, size_t end) {
      uint64_t range_rough = 0, range_glossy = 0, range_hsh = 0, range_shadow_rays = 0;
      for (size_t k = begin; k < end; ++k) {
        const PixelSurface& s = piece[k];
        const size_t i = first + k;
        img.triangle[i] = s.triangle;
        range_rough += s.lobe_counts & 0xffu;  // kernels/layers.cl lobe_count_shift
        range_glossy += (s.lobe_counts >> 8) & 0xffu;
        range_hsh += (s.lobe_counts >> 16) & 0xffu;
        img.depth[i] = s.triangle >= 0 ? scene_frame.length_to_world(s.depth) : 0.0f;
        const glm::vec3 world = s.triangle >= 0
                                    ? scene_frame.to_world(glm::vec3(s.position[0], s.position[1], s.position[2]))
                                    : glm::vec3(0.0f);
        range_shadow_rays += uint64_t(s.shadow_rays);
        for (int c = 0; c < 3; ++c) {
          img.direct[3 * i + c] = s.direct[c];
          img.emission[3 * i + c] = s.emission[c];
          img.albedo[3 * i + c] = s.albedo[c];
          img.normal[3 * i + c] = s.normal[c];
          img.position[3 * i + c] = world[c];
          img.color[3 * i + c] = s.emission[c] + s.direct[c];
        }
      }
      rough += range_rough;
      glossy += range_glossy;
      hsh += range_hsh;
      shadow_rays += range_shadow_rays;
    });
  });
  st.rough_pixels += rough;
  st.glossy_pixels += glossy;
  st.hsh_pixels += hsh;
  st.shadow_rays += shadow_rays;
  st.layers_s += seconds_since(t);

  IndirectFrame frame{gpu, scene, device_scene, gbuffer, direct, settings, img, layers};
  frame.progress = progress;
  frame.progress_done_before = progress_done_before;
  switch (settings.gi) {
    case GiMethod::none: break;
    case GiMethod::splat: splat_indirect(frame); break;
    case GiMethod::octree: octree_indirect(frame); break;
    case GiMethod::path: path_traced_indirect(frame); break;
  }
}

// Adds round's layers that path tracing fills to sum's (sum empty: takes them).
void add_round(RenderedImage& sum, const RenderedImage& round) {
  auto add = [](std::vector<float>& a, const std::vector<float>& b) {
    if (a.empty()) {
      a = b;
      return;
    }
    for (size_t i = 0; i < a.size(); ++i) a[i] += b[i];
  };
  add(sum.color, round.color);
  add(sum.direct, round.direct);
  add(sum.emission, round.emission);
  add(sum.albedo, round.albedo);
  add(sum.normal, round.normal);
  add(sum.indirect, round.indirect);
  add(sum.indirect_variance, round.indirect_variance);
  RenderStats& a = sum.stats;
  const RenderStats& b = round.stats;
  a.gbuffer_s += b.gbuffer_s;
  a.direct_s += b.direct_s;
  a.path_s += b.path_s;
  a.primary_rays += b.primary_rays;
  a.shadow_rays += b.shadow_rays;
  a.path_rays += b.path_rays;
  a.path_samples += b.path_samples;
  a.rough_pixels += b.rough_pixels;
  a.glossy_pixels += b.glossy_pixels;
  a.hsh_pixels += b.hsh_pixels;
}

// Path tracing over the pixels' area (PathSettings::pixel_area): settings.pixel_samples = s^2 rounds of the frame,
// round r's camera rays through a random point of cell r of an s x s grid over each pixel (stratified jitter), each
// with its share of the light and path samples, averaged. The position, depth and triangle layers are those of the
// round whose cell holds the pixel's centre. The BVH, the kernels and the buffers serve every round.
void path_trace_pixel_area(GpuContext& gpu, const Scene& scene, const DeviceScene& device_scene,
                           const SceneFrame& scene_frame, GBufferPass& gbuffer, DirectPass& direct,
                           LayerPass& layers, const CameraParams& camera, const RenderSettings& settings,
                           RenderedImage& img) {
  const unsigned side = pixel_sample_side(std::max(1u, settings.pixel_samples)), rounds = side * side;
  RenderSettings round_settings = samples_per_sub_pixel(settings, rounds);
  const unsigned strata = light_sample_strata(round_settings.light_samples);
  const unsigned centre_round = (side / 2) * side + side / 2;
  RenderedImage sum;
  sum.width = img.width;
  sum.height = img.height;
  sum.stats = img.stats;
  Progress progress("path tracing", size_t(settings.path.samples));
  for (unsigned r = 0; r < rounds; ++r) {
    CameraParams round_camera = camera;
    round_camera.jitter_seed = hash_u32(settings.seed ^ hash_u32(r + 0x6a697474u)) | 1u;  // never 0: jittered
    round_camera.jitter_cell = 1.0f / float(side);
    round_camera.jitter_origin[0] = float(r % side) / float(side);
    round_camera.jitter_origin[1] = float(r / side) / float(side);
    round_settings.seed = r == 0 ? settings.seed : hash_u32(settings.seed + 0x9e3779b9u * r);
    RenderedImage round;
    round.width = img.width;
    round.height = img.height;
    round.stats = img.stats;
    shade_frame(gpu, scene, device_scene, scene_frame, gbuffer, direct, layers, round_camera, strata, round_settings,
                round, &progress, size_t(r) * round_settings.path.samples);
    if (r == centre_round) {
      sum.position = std::move(round.position);
      sum.depth = std::move(round.depth);
      sum.triangle = std::move(round.triangle);
    }
    add_round(sum, round);
    sum.stats.program_s += round.stats.program_s - img.stats.program_s;  // the path pass's kernels, once cached
  }
  progress.finish();
  const float mean = 1.0f / float(rounds), variance_of_mean = mean * mean;
  for (std::vector<float>* layer : {&sum.color, &sum.direct, &sum.emission, &sum.albedo, &sum.normal, &sum.indirect})
    for (float& v : *layer) v *= mean;
  for (float& v : sum.indirect_variance) v *= variance_of_mean;  // independent rounds: the mean's variance
  sum.stats.light_samples = strata * strata * rounds;
  sum.stats.pixel_samples = rounds;
  sum.stats.rough_pixels /= rounds;
  sum.stats.glossy_pixels /= rounds;
  sum.stats.hsh_pixels /= rounds;
  img = std::move(sum);
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
  // The G-buffer's frame: the image's, or side times as wide and high with sub-pixels (render/pixel_samples.h).
  int frame_width = settings.width, frame_height = settings.height;
  resolve_resolution(cam, frame_width, frame_height);
  const unsigned side = std::max(1u, settings.sub_pixel_side);
  img.width = frame_width / int(side);
  img.height = frame_height / int(side);
  check_frame_fits(frame_width, frame_height, side, gpu.device_info());
  scene.check_extent();
  // The device traces and shades in coordinates centred on the scene and scaled to it (scene/scene_frame.h); the
  // position and depth layers and the records go back to world units below.
  const SceneFrame scene_frame = SceneFrame::fitted(scene);
  CameraParams params = camera_params(scene_frame.device_camera(cam), frame_width, frame_height);
  params.sub_pixel_side = int(settings.sub_pixel_side);
  const unsigned strata = light_sample_strata(settings.light_samples);
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
  // Kernel builds count in program_s, the probe's photon kernel's included (it was once left inside probe_s: 2 s of
  // a cold 1080p frame on an H200 that no build column showed).
  const TimeWithoutBuilds probe(gpu);
  const BounceChoice bounce_choice = choose_bounces(gpu, scene, device_scene, settings);
  st.probe_s = probe.seconds();
  settings.bounces = bounce_choice.bounces;
  settings.bounce_method = bounce_choice.method;
  st.bounces = bounce_choice.bounces;
  st.bounce_method = bounce_choice.method;
  st.bounces_chosen = bounce_choice.bounces_chosen;
  st.kept_per_bounce = bounce_choice.kept_per_bounce;
  log_info("compiling kernels for " + st.device);
  GBufferPass gbuffer(gpu, device_scene);
  DirectPass direct(gpu, device_scene);
  LayerPass layers(gpu, side, img.width, img.height);
  if (settings.layer_piece_pixels) layers.set_piece_pixels(settings.layer_piece_pixels);
  st.program_s = probe.builds();  // the probe's and these three passes'; later passes add their own

  if (settings.gi == GiMethod::path && settings.path.pixel_area)
    path_trace_pixel_area(gpu, scene, device_scene, scene_frame, gbuffer, direct, layers, params, settings, img);
  else
    shade_frame(gpu, scene, device_scene, scene_frame, gbuffer, direct, layers, params, strata, settings, img);
  for (CacheRecord& r : img.records) r = scene_frame.world_record(r);
  st.total_s = seconds_since(start);
  st.device_memory = gpu.memory_use();
  return img;
}

}  // namespace rcsplat
