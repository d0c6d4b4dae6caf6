#include "render/renderer.h"


#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <string>

#include "bvh/bvh8.h"
#include "cache/cache_settings.h"
#include "cl/device_scene.h"
#include "kernels/counter_random.h"
#include "kernels/hsh.h"
#include "passes/direct_pass.h"
#include "passes/glass_caustics_pass.h"
#include "passes/glass_mirror_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/layer_pass.h"
#include "passes/guide_cluster_pass.h"
#include "passes/light_guide_pass.h"
#include "passes/ray_queue.h"
#include "render/indirect.h"
#include "render/kept_records.h"
#include "render/bounce_choice.h"
#include "render/pixel_samples.h"
#include "scene/scene_frame.h"
#include "util/colour.h"
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
    throw Error("out of device memory: a " + frame + " frame needs at least " + gib(device_bytes) +
                " of device memory; '" + device.name + "' has " + gib(double(device.global_memory)) +
                " (--width, --height)");
  if (host_memory > 0.0 && host_bytes > host_memory)
    throw Error("out of host memory: a " + frame + " frame needs at least " + gib(host_bytes) +
                " of host memory; this machine has " + gib(host_memory) + " (--width, --height)");
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
  a.primary.gbuffer_s += b.primary.gbuffer_s;
  a.primary.direct_s += b.primary.direct_s;
  a.path.seconds += b.path.seconds;
  a.primary.primary_rays += b.primary.primary_rays;
  a.primary.shadow_rays += b.primary.shadow_rays;
  a.path.rays += b.path.rays;
  a.path.samples += b.path.samples;
  a.primary.rough_pixels += b.primary.rough_pixels;
  a.primary.glossy_pixels += b.primary.glossy_pixels;
  a.primary.hsh_pixels += b.primary.hsh_pixels;
}

}  // namespace

Renderer::Renderer(GpuContext& gpu, const Scene& scene, const std::set<std::string>& forced_switches,
                   const std::vector<TriangleRange>& moving_parts)
    : gpu_(gpu),
      scene_(scene),
      forced_switches_(forced_switches),
      moving_parts_(moving_parts),
      light_(std::make_unique<ViewIndependentLight>()),
      passes_(std::make_unique<MethodPasses>()) {
  StageTimer setup_time(setup_seconds_);
  BuildTimer builds(gpu_, setup_.program_s);
  scene_.check_extent();
  // The device traces and shades in coordinates centred on the scene and scaled to it (scene/scene_frame.h); the
  // position and depth layers and the records go back to world units.
  scene_frame_ = SceneFrame::fitted(scene_);
  log_info("building the BVH over " + std::to_string(scene_.triangle_count()) + " triangles");
  {
    // Only the device keeps the BVH: the host's copy goes once it is uploaded.
    Bvh8 still;
    if (moving_parts_.empty())
      still = build_bvh8(scene_frame_.device_positions(scene_));
    else
      moving_bvh_ = std::make_unique<MovingBvh>(scene_frame_.device_positions(scene_), moving_parts_);
    const Bvh8& bvh = moving_bvh_ ? moving_bvh_->tree() : still;
    scene_stats_.triangles = scene_.triangle_count();
    scene_stats_.bvh_nodes = bvh.nodes.size();
    scene_stats_.bvh_blocks = bvh.blocks.size();
    scene_stats_.bvh_depth = bvh.depth;
    setup_.scene.bvh_build_s = bvh.build_seconds;
    StageTimer timing(setup_.scene.upload_s);
    device_scene_ = std::make_unique<DeviceScene>(gpu_, scene_, bvh, forced_switches_, scene_frame_);
  }
  const std::array<unsigned, LOBE_KINDS>& lobes = device_scene_->lobe_counts();
  scene_stats_.lambertian_materials = lobes[LOBE_NONE];
  scene_stats_.rough_materials = lobes[LOBE_ROUGH];
  scene_stats_.glossy_materials = lobes[LOBE_GLOSSY];
  scene_stats_.hsh_materials = lobes[LOBE_HSH];
  scene_stats_.specular_brdf = device_scene_->has_specular_brdf();
  if (device_scene_->has_glass_caustics()) shoot_glass_caustic_map();
  // Every frame's first two programs, compiling while the plan's bounce probe and lobe table run; render() makes
  // their passes.
  GBufferPass::build_ahead(gpu_, *device_scene_);
  DirectPass::build_ahead(gpu_, *device_scene_);
  if (device_scene_->has_glass()) GlassMirrorPass::build_ahead(gpu_, *device_scene_);
  if (device_scene_->has_glass_caustics()) GlassCausticsPass::build_ahead(gpu_, *device_scene_);
}

MovingBvh::Changed Renderer::move_geometry(const std::vector<PartMove>& moved_parts, double& bvh_s, double& upload_s) {
  if (!moved_parts.empty() && !moving_bvh_) throw Error("this renderer was made without moving parts");
  MovingBvh::Changed rows;
  {
    StageTimer refit(bvh_s);
    std::vector<size_t> parts;
    for (const PartMove& m : moved_parts) parts.push_back(m.part);
    if (!parts.empty())
      rows = moving_bvh_->move([this](size_t i) { return scene_frame_.to_device(scene_.positions[i]); }, parts);
  }
  {
    StageTimer timing(upload_s);
    std::vector<TriangleRange> moved;
    for (const PartMove& m : moved_parts) moved.push_back(moving_parts_[m.part]);
    device_scene_->move(gpu_, scene_, moving_bvh_ ? &moving_bvh_->tree() : nullptr, rows, moved);
  }
  return rows;
}

void Renderer::forget_light_if_moved() {
  // Photons, clusters and the glass caustic map saw the scene as it was. A photon map is a density blurred over its
  // gather radius: a part that has moved less than that radius since the photons were shot changes its estimate by
  // less than the blur does, so the map is kept until the moves add up to the radius (the caustic map's radius, where
  // there is one, the same); a light that moved makes it again. The light guide only steers samples and goes with
  // the map. Made again, each is shot when a frame next asks for it. Held, it waits (hold_light).
  double radius = has_photons() ? INFINITY : 0.0;
  if (light_->photon_map) radius = std::min(radius, double(light_->photon_radius));
  if (light_->caustic_map) radius = std::min(radius, double(light_->caustic_radius));
  if ((!light_held_ && moved_since_photons_ > radius) || (!light_held_through_light_moves_ && lights_moved_since_photons_))
    forget_light();
}

bool Renderer::has_photons() const { return light_->photon_map || light_->caustic_map; }
bool Renderer::has_caustic_map() const { return light_->caustic_map != nullptr; }

size_t Renderer::move(const std::vector<PartMove>& moved_parts, bool lights_moved, double record_tolerance) {
  if (moved_parts.empty() && !lights_moved) {
    forget_light_if_moved();  // moves made while the light was held
    return 0;
  }
  StageTimer setup_time(setup_seconds_);
  const MovingBvh::Changed rows = move_geometry(moved_parts, setup_.scene.bvh_build_s, setup_.scene.upload_s);
  double largest = 0.0;
  for (const PartMove& m : moved_parts) largest = std::max(largest, m.displacement);
  moved_since_photons_ += largest;
  lights_moved_since_photons_ = lights_moved_since_photons_ || lights_moved;
  const bool had_photons = has_photons();
  forget_light_if_moved();
  if (!kept_records_) return 0;
  std::vector<SweptBox> swept;
  for (size_t i = 0; i < rows.swept.size(); ++i)
    swept.push_back({rows.swept[i].first, rows.swept[i].second,
                     float(moved_parts[i].displacement / scene_frame_.scale), rows.triangles[i]});
  size_t marked = 0;
  for (KeptRecords* records : {&kept_records_->irradiance, &kept_records_->radiance}) {
    // A light that moves changes every record's light but where a temporal window holds it (the look ahead). Where
    // no window follows it and there are photons (no windows, or a caustic map: sequence/walkthrough.cpp), every
    // record in view would be computed again at each frame; they go instead and placement puts what the view needs:
    // computed in place, the records of a lamp carried through Sponza piled up to 1.7 times a fresh frame's, and the
    // frame cost 1.3 times a fresh one.
    marked += lights_moved ? records->mark_all_moved() : records->mark_moved(swept, record_tolerance);
    if (lights_moved && had_photons && !lights_by_windows_) records->let_marked_go();
  }
  return marked;
}

void Renderer::forget_light() {
  light_ = std::make_unique<ViewIndependentLight>();
  moved_since_photons_ = 0.0;
  lights_moved_since_photons_ = false;
  if (device_scene_->has_glass_caustics()) shoot_glass_caustic_map();
  if (kept_records_) kept_records_->light = KeptLight{};
}

void Renderer::pose_for_look_ahead(const std::vector<PartMove>& moved_parts) {
  double bvh_s = 0.0, upload_s = 0.0;  // the caller times the look ahead as a whole
  move_geometry(moved_parts, bvh_s, upload_s);
}

// The light shot for a window's end (look_ahead_with_its_light), with its photons and clusters for a cache file.
struct Renderer::LightAhead {
  double time = 0.0;
  std::unique_ptr<ViewIndependentLight> light = std::make_unique<ViewIndependentLight>();
  KeptLight kept;
};

Renderer::LookAhead Renderer::look_ahead_with_its_light(double end, double sudden_change, const FramePlan& plan) {
  LookAhead result;
  if (!kept_records_ || !passes_ || !passes_->in_place.pass) return result;
  const RenderSettings& settings = plan.frame_settings();
  RenderedImage scratch;  // what the light's passes report; the caller times the look ahead as a whole
  if (!light_ahead_ || light_ahead_->time != end) {
    light_ahead_ = std::make_unique<LightAhead>();
    light_ahead_->time = end;
  }
  IndirectFrame ahead{gpu_, scene_, *device_scene_, *gbuffer_, *direct_, plan, settings, scratch, *layers_,
                      *light_ahead_->light, *passes_};
  ahead.kept_light = &light_ahead_->kept;
  // Shot on first use for this end (its photons kept beside it for a cache file, as the frame's are), and bound to
  // the batch's record pass; the next frame binds its own light again (frame_record_pass).
  RecordPass& records = *passes_->in_place.pass;
  records.begin_frame(attach_photon_map(ahead), settings.bounces);
  attach_light_guide(ahead, records);
  return look_ahead(end, sudden_change);
}

void Renderer::take_light_ahead(double now) {
  if (!light_ahead_ || light_ahead_->time != now) return;
  light_ = std::move(light_ahead_->light);
  moved_since_photons_ = 0.0;
  lights_moved_since_photons_ = false;
  if (kept_records_) kept_records_->light = std::move(light_ahead_->kept);
  light_ahead_.reset();
}

Renderer::LookAhead Renderer::look_ahead(double end, double sudden_change) {
  LookAhead result;
  if (!kept_records_ || !passes_) return result;
  MethodPasses::InPlaceBatch& batch = passes_->in_place;
  KeptRecords& kept = kept_records_->irradiance;
  const std::vector<size_t> in_place = kept.computed_in_place_this_frame();
  // Eviction may have taken some of the batch's records: then the pixels no longer line up, and none gets a window.
  if (!batch.pass || batch.pixels.empty() || in_place.size() != batch.pixels.size()) return result;
  std::vector<size_t> indices;  // those without a window yet (a second, shorter look ahead: --max-lag)
  std::vector<cl_uint> pixels;
  for (size_t i = 0; i < in_place.size(); ++i)
    if (!kept.has_window(in_place[i])) {
      indices.push_back(in_place[i]);
      pixels.push_back(batch.pixels[i]);
    }
  if (pixels.empty()) return result;
  const uint32_t count = uint32_t(pixels.size());
  const cl::Buffer candidates = gpu_.upload(pixels, CL_MEM_READ_ONLY, "records");
  // The frame is done with its records: the batch's slots take their light at `end`, from the same pixels and with
  // the same strata, so the two ends' noise is alike and the interpolation does not flicker.
  batch.pass->compute(gbuffer_->view(), candidates, count, batch.first, batch.hemisphere);
  const std::vector<CacheRecord> ahead = batch.pass->download(batch.first, count);
  result.computed = count;
  for (uint32_t i = 0; i < count; ++i) {
    const CacheRecord& now = kept.records()[indices[i]];
    const double l0 = luminance(now.irradiance), l1 = luminance(ahead[i].irradiance);
    const double change = std::fabs(l1 - l0) / std::max({l0, l1, 1e-30});
    if (!(change <= sudden_change)) continue;  // too sudden to interpolate: computed again as moves mark it
    kept.set_window(indices[i], light_of(ahead[i]), end);
    ++result.windows;
  }
  return result;
}

void Renderer::shoot_glass_caustic_map() {
  {
    // The light glass volumes pass: every kernel's SCENE_ARGS carry it from here on.
    StageTimer timing(scene_stats_.glass_caustic_s);
    log_info("shooting " + std::to_string(scene_.glass_light.photons) + " photon paths through glass volumes");
    const GlassCausticMap map =
        shoot_glass_caustics(gpu_, *device_scene_, device_surface_area(scene_, scene_frame_),
                             glass_volume_spheres(scene_, scene_frame_), scene_.glass_light);
    scene_stats_.glass_caustics = true;
    scene_stats_.glass_caustic_paths = map.paths;
    scene_stats_.glass_caustic_photons = map.photons;
    scene_stats_.glass_caustic_radius = scene_frame_.length_to_world(map.radius);
    scene_stats_.glass_caustic_largest_radius = scene_frame_.length_to_world(map.largest_radius);
  }
}

void Renderer::build_programs_ahead(const FramePlan& plan) {
  const FramePasses& passes = plan.passes;
  const DeviceScene& scene = *device_scene_;
  LayerPass::build_ahead(gpu_);
  if (passes.path) PathPass::build_ahead(gpu_, scene);
  if (!passes.records) return;
  // The photon map, the caustic map and the light guide shoot their photons with the light guide's kernel.
  if (passes.photon_map || passes.caustic_map || passes.light_guide) LightGuidePass::build_ahead(gpu_, scene);
  if (passes.light_guide) GuideClusterPass::build_ahead(gpu_);
  if (passes.photon_map) PhotonMapPass::build_ahead(gpu_);
  if (passes.caustic_map) CausticMapPass::build_ahead(gpu_);
  const unsigned theta_strata = largest_theta_strata(plan.cache());
  RecordPass::build_ahead(gpu_, scene, theta_strata, false, passes.photon_map, passes.caustic_map);
  if (passes.record_trace == RecordTrace::wavefront) RayQueue::build_ahead(gpu_, scene);  // its queued rays
  if (passes.device_placement) {
    PlacementPass::build_ahead(gpu_);
    SplatPass::build_ahead(gpu_);
  }
  if (passes.radiance_records) {
    RecordPass::build_ahead(gpu_, scene, theta_strata, true, passes.photon_map, false);
    HshRecordPass::build_ahead(gpu_);
    RadianceSplatPass::build_ahead(gpu_);
  }
  if (passes.glossy) GlossyPass::build_ahead(gpu_, scene, passes.glossy_samples_hsh);
  if (passes.world_record_grid) WorldRecordGridPass::build_ahead(gpu_);
  ComposePass::build_ahead(gpu_, scene, passes.radiance_records);
}

Renderer::~Renderer() = default;

double Renderer::kept_per_bounce() {
  if (!kept_per_bounce_) {
    // Kernel builds count in program_s, the probe's photon kernel's included (it was once left inside probe_s: 2 s
    // of a cold 1080p frame on an H200 that no build column showed).
    StageTimer setup_time(setup_seconds_);
    StageTimer probe(setup_.bounces.probe_s, gpu_, setup_.program_s);
    kept_per_bounce_ = rcsplat::kept_per_bounce(gpu_, *device_scene_);
  }
  return *kept_per_bounce_;
}

const RadianceLobeTable& Renderer::lobe_table(unsigned seed) {
  if (!lobe_table_ || lobe_table_seed_ != seed) {
    StageTimer setup_time(setup_seconds_);
    StageTimer table(setup_.radiance.lobe_table_s, gpu_, setup_.program_s);
    lobe_table_ = std::make_unique<RadianceLobeTable>(radiance_lobe_table(gpu_, *device_scene_, seed));
    lobe_table_seed_ = seed;
  }
  return *lobe_table_;
}

FramePlan Renderer::plan(const RenderSettings& request) {
  check_request(request);
  if (request.forced_switches != forced_switches_)
    throw Error("this renderer was made with other forced kernel switches than the request's");
  FramePlan p;
  p.settings = request;
  RenderSettings& s = p.settings;
  p.camera = choose_camera(scene_, s.camera, s.camera_overrides);
  resolve_resolution(p.camera, s.width, s.height);
  if (s.pixel_samples == 0) s.pixel_samples = default_pixel_samples(s, s.width, s.height);
  const unsigned side = pixel_sample_side(s.pixel_samples);
  // Path tracing over the pixel's area traces rounds of the image's frame itself.
  const bool rounds = s.gi == GiMethod::path && s.path.pixel_area;
  p.side = rounds ? 1 : side;
  p.rounds = rounds ? side * side : 1;
  if (std::max(s.width, s.height) * int(p.side) > 16384)
    throw Error("--pixel-samples " + std::to_string(s.pixel_samples) + " at " + std::to_string(s.width) + "x" +
                std::to_string(s.height) + " needs a sub-pixel frame above 16384 pixels wide or high");
  check_frame_fits(p.frame_width(), p.frame_height(), p.side, gpu_.device_info());

  const bool cache = s.gi == GiMethod::splat || s.gi == GiMethod::octree;
  if (s.bounce_method == BounceMethod::photons && s.bounces != 1 && cache && scene_.environment.present())
    throw Error("--bounce-method photons: the photons come from the lights and an environment's peak, not from its "
                "gathered part, so a sky's later bounces would be lost; use --bounce-method path with --sky or "
                "--environment");
  const BounceChoice bounces = choose_bounces(scene_, s, [this] { return kept_per_bounce(); });
  s.bounces = bounces.bounces;
  s.bounce_method = bounces.method;
  p.bounces_chosen = bounces.bounces_chosen;
  p.kept_per_bounce = bounces.kept_per_bounce;
  p.passes = decide_frame_passes(s, device_scene_->lobe_counts(), gpu_.groups().record_trace);

  // Radiance caching (the splat's LOBE_HSH pixels): the order from the lobe table unless the request gives one.
  if (p.passes.radiance_records) {
    const RadianceLobeTable& lobes = lobe_table(s.seed);
    if (s.hsh_order == 0) s.hsh_order = automatic_hsh_order(lobes);
    p.hsh_captured_energy = hsh_captured_energy(lobes, s.hsh_order);
    p.radiance_accuracy = radiance_accuracy(lobes, s.cache.accuracy);
  }

  if (cache) scale_placement_to_image(s.cache, s.height);
  // Derived again by each frame; here once to refuse what cannot be divided among the sub-pixels (--spp).
  const RenderSettings frame = p.frame_settings();
  const unsigned light_samples = rounds ? samples_per_sub_pixel(s, p.rounds).light_samples : frame.light_samples;
  p.light_strata = light_sample_strata(light_samples);
  return p;
}

// Primary visibility through `camera`, direct light and the indirect light of one frame (or one round of path
// tracing over the pixel's area) into img; progress: the path tracer's, shared by rounds.
void Renderer::shade_frame(const FramePlan& plan, const CameraParams& camera, const RenderSettings& settings,
                           RenderedImage& img, Progress* progress, size_t progress_done_before) {
  GBufferPass& gbuffer = *gbuffer_;
  DirectPass& direct = *direct_;
  LayerPass& layers = *layers_;
  const unsigned strata = plan.light_strata;
  RenderStats& st = img.stats;
  {
    StageTimer timing(st.primary.gbuffer_s);
    gbuffer.run(camera);
  }
  {
    StageTimer timing(st.primary.direct_s);
    const bool cache = plan.passes.records;
    const unsigned sub_pixels = unsigned(gbuffer.view().sub_pixel_side * gbuffer.view().sub_pixel_side);
    const DirectRunStats run = direct.run(gbuffer.view(), strata, settings.seed,
                                          cache && settings.light_adaptive ? settings.light_samples * sub_pixels : 0);
    if (run.rounds) {
      st.primary.light_rounds = run.rounds;
      st.primary.light_mean_samples = double(run.samples) / double(std::max<uint64_t>(run.sampled_sub_pixels, 1)) *
                                      double(sub_pixels);
      st.primary.light_refined_pixels = run.refined_pixels;
    }
    if (glass_caustics_)  // the light glass volumes passed, which shadow rays leave to the glass caustic map
      glass_caustics_->add_to(gbuffer.view(), direct.radiance());
    gbuffer.weigh_through_glass(direct.radiance());  // a pixel that looks through glass sees its light through it
    if (glass_mirror_)  // and the lit surfaces its glass mirrors, as many paths as light samples
      glass_mirror_->run(gbuffer.view(), direct.radiance(), std::max(settings.light_samples, 1u),
                         hash_u32(settings.seed ^ STREAM_GLASS_MIRROR),
                         settings.gi == GiMethod::none ? 0u : std::max(settings.bounces, 1u));
  }

  StageTimer layers_timing(st.primary.layers_s);
  const size_t pixels = layers.pixel_count();
  img.color.resize(pixels * 3);
  st.primary.primary_rays = gbuffer.view().pixel_count();
  // The cache methods' colour comes whole from the device's composition (indirect_compose.cpp); path tracing and
  // direct light alone add up emission, direct and their indirect here.
  const bool colour_on_host = !plan.passes.records;
  if (layers_stay_on_device(settings)) {
    const std::array<uint64_t, LOBE_KINDS> lobes = layers.count_lobes(gbuffer.view());
    st.primary.rough_pixels += lobes[LOBE_ROUGH];
    st.primary.glossy_pixels += lobes[LOBE_GLOSSY];
    st.primary.hsh_pixels += lobes[LOBE_HSH];
    st.primary.shadow_rays += layers.sum_alpha(gbuffer.view(), direct.radiance());
    if (colour_on_host) layers.direct_colour(gbuffer.view(), direct.radiance(), LayerPass::rgb_into(img.color));
  } else {
    surface_layers(img, colour_on_host);
  }
  layers_timing.stop();

  IndirectFrame frame{gpu_, scene_, *device_scene_, gbuffer, direct, plan, settings, img, layers, *light_, *passes_};
  frame.camera = &camera;
  if (settings.keep_records && settings.gi == GiMethod::splat) {
    kept_records().set_capacity(settings.kept_records_capacity);
    frame.kept_records = &kept_records_->irradiance;
    frame.kept_radiance_records = &kept_records_->radiance;
    frame.kept_light = &kept_records_->light;
  } else {
    kept_records_.reset();
  }
  frame.lobe_table = lobe_table_.get();
  frame.progress = progress;
  frame.progress_done_before = progress_done_before;
  switch (settings.gi) {
    case GiMethod::none: break;
    case GiMethod::splat: splat_indirect(frame); break;
    case GiMethod::octree: octree_indirect(frame); break;
    case GiMethod::path: path_traced_indirect(frame); break;
  }
}

// The layers a frame's surface gives (PixelSurface): downloaded in pieces and filled in, with the summary's counts;
// colour_on_host: the colour starts from emission + direct here (path tracing, direct light alone).
void Renderer::surface_layers(RenderedImage& img, bool colour_on_host) {
  LayerPass& layers = *layers_;
  const SceneFrame& scene_frame = scene_frame_;
  const size_t pixels = layers.pixel_count();
  img.direct.resize(pixels * 3);
  img.emission.resize(pixels * 3);
  img.albedo.resize(pixels * 3);
  img.normal.resize(pixels * 3);
  img.position.resize(pixels * 3);
  img.depth.resize(pixels);
  img.triangle.resize(pixels);
  std::atomic<uint64_t> rough{0}, glossy{0}, hsh{0}, shadow_rays{0};
  layers.surface(gbuffer_->view(), direct_->radiance(), [&](size_t first, const PixelSurface* piece, size_t count) {
    parallel_ranges(count, [&](size_t begin, size_t end) {
      uint64_t range_rough = 0, range_glossy = 0, range_hsh = 0, range_shadow_rays = 0;
      for (size_t k = begin; k < end; ++k) {
        const PixelSurface& s = piece[k];
        const size_t i = first + k;
        img.triangle[i] = s.triangle;
        range_rough += lobe_count(s.lobe_counts, LOBE_ROUGH);
        range_glossy += lobe_count(s.lobe_counts, LOBE_GLOSSY);
        range_hsh += lobe_count(s.lobe_counts, LOBE_HSH);
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
          if (colour_on_host) img.color[3 * i + c] = s.emission[c] + s.direct[c];
        }
      }
      rough += range_rough;
      glossy += range_glossy;
      hsh += range_hsh;
      shadow_rays += range_shadow_rays;
    });
  });
  RenderStats& st = img.stats;
  st.primary.rough_pixels += rough;
  st.primary.glossy_pixels += glossy;
  st.primary.hsh_pixels += hsh;
  st.primary.shadow_rays += shadow_rays;
}

// Path tracing over the pixels' area (PathSettings::pixel_area): plan.rounds = s^2 rounds of the frame, round r's
// camera rays through a random point of cell r of an s x s grid over each pixel (stratified jitter), each with its
// share of the light and path samples, averaged. The position, depth and triangle layers are those of the round whose
// cell holds the pixel's centre. The BVH, the kernels and the buffers serve every round.
void Renderer::path_trace_pixel_area(const FramePlan& plan, const CameraParams& camera, RenderedImage& img) {
  const RenderSettings settings = plan.frame_settings();
  const unsigned rounds = plan.rounds, side = pixel_sample_side(rounds);
  RenderSettings round_settings = samples_per_sub_pixel(settings, rounds);
  const unsigned centre_round = (side / 2) * side + side / 2;
  RenderedImage sum;
  sum.width = img.width;
  sum.height = img.height;
  sum.stats = img.stats;
  Progress progress("path tracing", size_t(settings.path.samples));
  for (unsigned r = 0; r < rounds; ++r) {
    CameraParams round_camera = camera;
    round_camera.jitter_seed = hash_u32(settings.seed ^ hash_u32(r + STREAM_PIXEL_JITTER)) | 1u;  // never 0: jittered
    round_camera.jitter_cell = 1.0f / float(side);
    round_camera.jitter_origin[0] = float(r % side) / float(side);
    round_camera.jitter_origin[1] = float(r / side) / float(side);
    round_settings.seed = r == 0 ? settings.seed : hash_u32(settings.seed + STREAM_ROUND_STEP * r);
    RenderedImage round;
    round.width = img.width;
    round.height = img.height;
    round.stats = img.stats;
    shade_frame(plan, round_camera, round_settings, round, &progress, size_t(r) * round_settings.path.samples);
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
  sum.stats.primary.light_samples = plan.light_strata * plan.light_strata * rounds;
  sum.stats.primary.pixel_samples = rounds;
  sum.stats.primary.rough_pixels /= rounds;
  sum.stats.primary.glossy_pixels /= rounds;
  sum.stats.primary.hsh_pixels /= rounds;
  img = std::move(sum);
}

RenderedImage Renderer::render(const FramePlan& plan) {
  const auto start = Clock::now();
  gpu_.restart_memory_peak();
  RenderedImage img;
  RenderStats& st = img.stats;
  // A plan made before another seed's frame: its lobe table again (kept per seed, as the photon map and the guide).
  if (plan.passes.radiance_records) lobe_table(plan.settings.seed);
  // The setup this frame pays for (all of it for a renderer's first frame, none for a later one with the same plan).
  st.scene = scene_stats_;
  st.scene.bvh_build_s = setup_.scene.bvh_build_s;
  st.scene.upload_s = setup_.scene.upload_s;
  st.bounces.probe_s = setup_.bounces.probe_s;
  st.radiance.lobe_table_s = setup_.radiance.lobe_table_s;
  st.program_s = setup_.program_s;
  const double setup_seconds = setup_seconds_;
  setup_ = RenderStats{};
  setup_seconds_ = 0.0;
  BuildTimer builds(gpu_, st.program_s);

  st.device = gpu_.device_info().name;
  st.gi = plan.settings.gi;
  const FrameBounces bounces = plan.bounces();
  st.bounces.count = bounces.count;
  st.bounces.method = bounces.method;
  st.bounces.chosen = bounces.chosen;
  st.bounces.kept_per_bounce = bounces.kept_per_bounce;
  st.primary.light_samples = plan.light_strata * plan.light_strata;
  const FrameImage image = plan.image();
  img.width = image.width;
  img.height = image.height;

  CameraParams params = camera_params(scene_frame_.device_camera(plan.camera), image.frame_width, image.frame_height);
  params.sub_pixel_side = int(image.side);
  // One method's passes at a time: another method's frame frees them before making its own.
  if (passes_->method != plan.settings.gi) {
    passes_ = std::make_unique<MethodPasses>();
    passes_->method = plan.settings.gi;
  }
  // Not in plan(): a plan may be made only to be read (`rcsplat info`, tests), and would pay for every build.
  build_programs_ahead(plan);
  if (!gbuffer_) {
    log_info("compiling kernels for " + gpu_.device_info().name);
    gbuffer_ = std::make_unique<GBufferPass>(gpu_, *device_scene_);
    direct_ = std::make_unique<DirectPass>(gpu_, *device_scene_);
    if (device_scene_->has_glass()) glass_mirror_ = std::make_unique<GlassMirrorPass>(gpu_, *device_scene_);
    if (device_scene_->has_glass_caustics())
      glass_caustics_ = std::make_unique<GlassCausticsPass>(gpu_, *device_scene_);
  }
  if (!layers_ || layers_->side() != image.side || layers_->out_width() != image.width ||
      layers_->out_height() != image.height)
    layers_ = std::make_unique<LayerPass>(gpu_, image.side, image.width, image.height);
  layers_->set_piece_pixels(plan.settings.layer_piece_pixels);
  builds.stop();

  if (plan.rounds > 1)
    path_trace_pixel_area(plan, params, img);
  else
    shade_frame(plan, params, plan.frame_settings(), img);
  for (CacheRecord& r : img.records) r = scene_frame_.world_record(r);
  if (plan.side > 1) {
    const unsigned n = plan.side * plan.side;
    st.primary.pixel_samples = n;
    st.primary.light_samples *= n;
    st.path.samples *= n;
  }
  st.total_s = setup_seconds + seconds_since(start);
  st.device_memory = gpu_.memory_use();
  return img;
}

KeptCache& Renderer::kept_records() {
  if (!kept_records_) kept_records_ = std::make_unique<KeptCache>(RenderSettings{}.kept_records_capacity);
  return *kept_records_;
}

RenderedImage render(GpuContext& gpu, const Scene& scene, const RenderSettings& settings) {
  check_request(settings);  // before the BVH is built
  Renderer renderer(gpu, scene, settings.forced_switches);
  return renderer.render(renderer.plan(settings));
}

}  // namespace rcsplat
