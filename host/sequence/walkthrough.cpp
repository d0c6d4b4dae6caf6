#include "sequence/walkthrough.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "cl/device_info.h"
#include "render/kept_records.h"
#include "render/render_output.h"
#include "scene/scene_animator.h"
#include "sequence/cache_merge.h"
#include "sequence/camera_path.h"
#include "sequence/record_times.h"
#include "sequence/video.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/frame_pattern.h"
#include "util/log.h"
#include "util/memory_use.h"
#include "util/paths.h"

namespace rcsplat {
namespace {

constexpr long long kMaxFrames = 1000000;

CameraPath choose_path(const WalkthroughRequest& o, const Scene& scene) {
  const CameraOverrides& overrides = o.render.settings.camera_overrides;
  const bool overridden = overrides.eye || overrides.target || overrides.up || overrides.fov_degrees;
  if (!o.keyframes.empty() && o.orbit_seconds > 0.0) throw Error("animate: give --keyframes or --orbit, not both");
  if (o.orbit_seconds > 0.0)
    return orbit_camera_path(choose_camera(scene, o.render.settings.camera, overrides), o.orbit_seconds,
                             o.orbit_degrees);
  if (overridden)
    throw Error(
        "animate: --eye, --target, --up and --fov set where an --orbit starts; a keyframe file or the scene's "
        "animation places the camera itself");
  if (!o.keyframes.empty()) return read_keyframe_camera_path(o.keyframes);
  if (o.render.scene_path.empty())
    throw Error("animate: the built-in Cornell box has no animation; give --orbit SECONDS or --keyframes FILE");
  // Every cache mode follows a moving scene (FrameRenderers; sequence/record_times.h); what no rigid move follows
  // (skins, morph weights) SceneAnimator refuses but with --cache-per-frame.
  return gltf_camera_path(scene, o.render.settings.camera, o.animation, true);
}

// The PNG frame pattern the MP4 preview is made from: the first PNG output.
std::string png_pattern(const WalkthroughRequest& o) {
  for (const std::string& out : o.render.outputs)
    if (lower_extension(out) == ".png") return out;
  return "";
}

// The frames a request renders and the scene's renderer for each: one Renderer for a still scene. A scene the path's
// animation moves (choose_path refuses it but with records kept or a cache per frame):
// - with records kept, one Renderer over a copy of the scene that a SceneAnimator poses at each frame's time: the
//   moving parts' BVH is refitted, what they changed written to the device, and the kept records their move may
//   have changed dropped, to be placed again (Renderer::move);
// - with a cache per frame, the scene loaded again in each frame's pose with a renderer of its own, as `render`
//   would render that pose (skins and morph weights too).
class FrameRenderers {
 public:
  FrameRenderers(GpuContext& gpu, const WalkthroughRequest& o, const Scene& scene, const CameraPath& path)
      : gpu_(gpu), o_(o), scene_(scene), path_(path), moves_(path.moves_scene_animation >= 0) {
    if (!moves_) {
      renderer_ = std::make_unique<Renderer>(gpu_, scene_, o_.render.settings.forced_switches);
    } else if (o_.cache != CacheMode::per_frame) {
      animator_.emplace(scene_, path.moves_scene_animation);
      posed_ = std::make_unique<Scene>(scene_);
      std::vector<TriangleRange> parts;
      for (const size_t m : animator_->moving()) {
        const Scene::Mover& mover = scene_.movers[m];
        part_of_.push_back(mover.triangle_count ? long(parts.size()) : -1);
        if (mover.triangle_count) parts.push_back({mover.first_triangle, mover.triangle_count});
      }
      renderer_ = std::make_unique<Renderer>(gpu_, *posed_, o_.render.settings.forced_switches, parts);
      bool moves_a_light = false;
      for (const size_t m : animator_->moving()) moves_a_light = moves_a_light || scene_.movers[m].light >= 0;
      renderer_->follow_lights_by_windows(moves_a_light && o_.cache == CacheMode::kept && o_.temporal_window > 1);
    }
  }
  Renderer& for_frame(long long frame) {
    if (!moves_) return *renderer_;
    if (animator_) {
      const double time = double(frame) / o_.fps;
      renderer_->kept_records().irradiance.set_time(time);
      renderer_->kept_records().radiance.set_time(time);
      // Records kept: the light is shot again at the frames --light-every divides; a light that moves shoots it at
      // once unless windows follow it, whose look ahead shoots it for their ends (take_light_ahead).
      const bool light_frame = frame % o_.light_every == 0;
      if (o_.cache == CacheMode::kept)
        renderer_->hold_light(!light_frame, renderer_->follows_lights_by_windows() && !light_frame);
      bool lights = false;
      const std::vector<Renderer::PartMove> parts = pose(time, lights);
      renderer_->move(parts, lights, o_.moved_record_tolerance);
      renderer_->take_light_ahead(time);
      return *renderer_;
    }
    renderer_.reset();  // before the scene it renders from
    posed_ = std::make_unique<Scene>(
        load_scene(o_.render, ScenePose{path_.moves_scene_animation, double(frame) / o_.fps}));
    renderer_ = std::make_unique<Renderer>(gpu_, *posed_, o_.render.settings.forced_switches);
    return *renderer_;
  }
  Renderer& current() { return *renderer_; }
  bool animated() const { return animator_.has_value(); }
  // The time the records of this walkthrough hold after frame `frame` (still: none), by key frame for a pre-pass.
  RecordTimes times(long long frame, bool by_key_frame) const {
    if (!animator_) return {};
    return {path_.moves_scene_animation, by_key_frame, o_.fps, by_key_frame ? 0.0 : double(frame) / o_.fps};
  }
  // A fixed cache's key frame's light (photon map, caustic map, light guide), shot where the scene stands at key frame
  // `key`: the scene posed there, every record and the light dropped, and the key frame rendered at 16 x 16 pixels
  // (the light does not depend on the view or the resolution), then the scene posed back at frame `frame`. The frames
  // from one key frame to the next share it, so that a frame depends on its key frame alone, whatever task renders
  // it. Adds the work to `stats`.
  KeptLight key_frame_light(long long key, long long frame, RenderSettings at_key, RenderStats& stats) {
    const auto start = std::chrono::steady_clock::now();
    bool lights = false;
    renderer_->pose_for_look_ahead(pose(double(key) / o_.fps, lights));
    renderer_->forget_light();
    KeptCache& kept = renderer_->kept_records();
    kept.irradiance.drop_records();
    kept.radiance.drop_records();
    at_key.width = at_key.height = 16;
    at_key.color_only = true;
    const RenderedImage shot = renderer_->render(renderer_->plan(at_key));
    KeptLight light = kept.light;
    renderer_->pose_for_look_ahead(pose(double(frame) / o_.fps, lights));
    stats.photon_map.seconds += shot.stats.photon_map.seconds;
    stats.total_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return light;
  }
  // How far the scene moved between two times, for records made at one and used at the other.
  std::optional<RecordMoves> record_moves() const {
    if (!animator_) return std::nullopt;
    return RecordMoves(scene_, *animator_, renderer_->device_scene().frame(), o_.moved_record_tolerance);
  }
  // Records read from a cache file (or put back from a fixed one) whose times `times` gives, brought to frame
  // `frame`: the scene posed there without marking anything, then each record marked by what moved since its own
  // time (RecordMoves::bring_to), to be computed again where it stands or to go. Where a light moved since a
  // single-time file's records, the photons they came with go too.
  // `let_go`: marked records go rather than being computed again (a fixed cache of many key frames' records).
  void bring_records_to(long long frame, const RecordTimes& times, bool let_go = false) {
    if (!animator_) return;
    const double time = double(frame) / o_.fps;
    bool lights = false;
    const std::vector<Renderer::PartMove> parts = pose(time, lights);
    if (!parts.empty()) renderer_->pose_for_look_ahead(parts);
    KeptCache& kept = renderer_->kept_records();
    RecordMoves moves = *record_moves();
    for (KeptRecords* records : {&kept.irradiance, &kept.radiance}) {
      records->set_time(time);
      moves.bring_to(*records, times, time);
      if (let_go) records->let_marked_go();
    }
    if (!times.by_key_frame && moves.between(times.time, time).lights) renderer_->forget_light();
  }
  const Scene& scene() const { return posed_ ? *posed_ : scene_; }
  // Before any frame is written: a pose no rigid move follows at any of the frames' times is refused now, not after
  // the frames before it were rendered.
  void check_poses(long long first, long long last) const {
    if (!animator_) return;
    for (long long frame = first; frame <= last; ++frame) animator_->check(*posed_, double(frame) / o_.fps);
  }

  // After frame `frame` (records kept through a moving scene): the records it computed again in place, computed
  // once more with the scene posed at the end of their temporal window, so that the frames before it interpolate
  // (Renderer::look_ahead); those too sudden for the window get one of max_lag + 1 frames. A light that moves is
  // posed at the end too, so that the records follow it as temporal radiance caching's gradients do; where the
  // frame's light holds photons, they are shot for the end as well (Renderer::look_ahead_with_its_light), since the
  // frame's would carry the lamp's later bounces from where it was: on a lamp carried through Sponza that lag
  // darkened the indirect light by 4.5% (benchmarks/RESULTS.md). Adds what it did to the frame's row.
  void look_ahead(long long frame, long long last, const FramePlan& plan, RenderStats& stats) {
    if (!animator_ || o_.temporal_window <= 1) return;
    // A caustic map is not shot ahead (Renderer::look_ahead_with_its_light): a light that moves lets records go.
    if (renderer_->has_caustic_map()) renderer_->follow_lights_by_windows(false);
    const bool lights_by_windows = renderer_->follows_lights_by_windows();
    if (renderer_->kept_records().irradiance.computed_in_place_this_frame().empty()) return;
    const auto start = std::chrono::steady_clock::now();
    const double now = double(frame) / o_.fps;
    // (window length, the change across it beyond which a record waits for a shorter window or none)
    std::vector<std::pair<long long, double>> looks{{o_.temporal_window, o_.max_lag + 1 >= o_.temporal_window ? INFINITY : 0.25}};
    if (o_.max_lag >= 1 && o_.max_lag + 1 < o_.temporal_window) looks.push_back({o_.max_lag + 1, INFINITY});
    for (const auto& [length, sudden] : looks) {
      long long end = std::min(frame + length, last);
      // Windows over a light that moves end on the frames the window's length divides, so that the light shot for an
      // end serves every window that ends there, and then the frame itself.
      if (lights_by_windows) end = std::min((frame / o_.temporal_window + 1) * o_.temporal_window, last);
      if (end <= frame) break;
      bool lights = false;
      renderer_->pose_for_look_ahead(pose(double(end) / o_.fps, lights));
      const bool photons = lights && renderer_->has_photons();
      if (!photons || lights_by_windows) {
        const Renderer::LookAhead done =
            photons ? renderer_->look_ahead_with_its_light(double(end) / o_.fps, sudden, plan)
                    : renderer_->look_ahead(double(end) / o_.fps, sudden);
        stats.kept_records.ahead += done.computed;
        stats.kept_records.windows += done.windows;
      }
      renderer_->pose_for_look_ahead(pose(now, lights));  // the animator too, for the next move
      if (photons || lights_by_windows) break;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.kept_records.ahead_s += seconds;
    stats.total_s += seconds;
  }

 private:
  GpuContext& gpu_;
  const WalkthroughRequest& o_;
  const Scene& scene_;
  const CameraPath& path_;
  const bool moves_;
  std::optional<SceneAnimator> animator_;  // records kept through a moving scene
  std::vector<long> part_of_;              // each moving mover's part of the renderer's BVH (-1: a light alone)
  std::unique_ptr<Scene> posed_;
  std::unique_ptr<Renderer> renderer_;

  // Poses the scene copy at `time`: the parts that moved since the last pose and how far, and whether a light did.
  std::vector<Renderer::PartMove> pose(double time, bool& lights) {
    const std::vector<size_t> changed = animator_->pose(*posed_, time);
    std::vector<Renderer::PartMove> parts;
    lights = false;
    for (const size_t i : changed) {
      if (part_of_[i] >= 0) parts.push_back({size_t(part_of_[i]), animator_->last_displacement(i)});
      lights = lights || posed_->movers[animator_->moving()[i]].light >= 0;
    }
    return parts;
  }
};

}  // namespace

const char* cache_mode_name(CacheMode mode) {
  switch (mode) {
    case CacheMode::kept: return "kept_records";
    case CacheMode::per_frame: return "per_frame";
    case CacheMode::fixed: return "fixed";
    case CacheMode::pre_pass: return "pre_pass";
    case CacheMode::merge: return "merge";
  }
  return "?";
}

CacheMode cache_mode_from_flags(bool per_frame, bool fixed, bool pre_pass, bool merge) {
  std::vector<std::string> given;
  if (per_frame) given.push_back("--cache-per-frame");
  if (fixed) given.push_back("--cache-fixed");
  if (pre_pass) given.push_back("--cache-every");
  if (merge) given.push_back("--cache-merge");
  if (given.size() > 1) {
    std::string names;
    for (size_t i = 0; i < given.size(); ++i) names += (i ? " and " : "") + given[i];
    throw Error(names + ": one cache mode a run (a cache per frame, a fixed cache, a pre-pass task or a merge)");
  }
  return per_frame ? CacheMode::per_frame
         : fixed   ? CacheMode::fixed
         : pre_pass ? CacheMode::pre_pass
         : merge    ? CacheMode::merge
                    : CacheMode::kept;
}

void check_walkthrough(const WalkthroughRequest& o) {
  check_request(o.render.settings);
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) throw Error("--fps must be above 0 and at most 1000");
  if (o.temporal_window < 1 || o.temporal_window > 240) throw Error("--temporal-window must be 1 to 240 frames");
  if (o.max_lag < 0 || o.max_lag >= o.temporal_window)
    throw Error("--max-lag must be 0 to --temporal-window - 1 (" + std::to_string(o.temporal_window - 1) + ") frames");
  if (o.light_every < 1 || o.light_every > 240) throw Error("--light-every must be 1 to 240 frames");
  const RenderJob& job = o.render;
  const CacheMode mode = o.cache;
  const bool pre_pass = mode == CacheMode::pre_pass, merging = mode == CacheMode::merge;
  if ((!job.cache_in.empty() || !job.cache_out.empty()) && mode == CacheMode::per_frame)
    throw Error("--cache-in and --cache-out: with --cache-per-frame no record is kept to read or write");
  if (mode == CacheMode::fixed && job.cache_in.empty())
    throw Error("--cache-fixed: needs --cache-in, the cache file every frame starts from");
  if (o.skip_existing && mode != CacheMode::fixed && mode != CacheMode::per_frame)
    throw Error("--skip-existing: without --cache-fixed or --cache-per-frame each frame reads the records the frames "
                "before it placed, so a frame rendered after a skipped one would differ from a whole run's");
  if (mode == CacheMode::fixed && !job.cache_out.empty())
    throw Error("--cache-fixed and --cache-out: a fixed cache keeps nothing a frame places, so there is nothing new to "
                "write");
  if (pre_pass && o.cache_every < 1) throw Error("--cache-every: a key frame every K frames needs K >= 1");
  if (merging && o.cache_merge.empty()) throw Error("--cache-merge: name the pre-pass parts to merge");
  if (pre_pass || merging) {
    const char* name = pre_pass ? "--cache-every" : "--cache-merge";
    if (job.cache_out.empty()) throw Error(std::string(name) + ": needs --cache-out, the file it writes");
    if (!job.cache_in.empty() || o.skip_existing)
      throw Error(std::string(name) +
                  ": a pre-pass starts each key frame from no records; leave out --cache-in, --cache-fixed, "
                  "--cache-per-frame and --skip-existing");
    if (!o.mp4_path.empty()) throw Error(std::string(name) + ": renders the key frames only; leave out --mp4");
    if (merging && !job.outputs.empty()) throw Error("--cache-merge: renders no frame; leave out -o");
    if (merging && !o.stats_path.empty()) throw Error("--cache-merge: renders no frame; leave out --stats");
  }
  if (job.outputs.empty() && !pre_pass && !merging) throw Error("animate: give at least one output with -o frames/%04d.exr");
  for (const std::string& out : job.outputs) {
    (void)FramePattern(out, "-o");  // throws for a pattern without one frame number
    if (!is_output_format(out)) throw Error(out + ": unknown output format (use " + output_formats() + ")");
  }
  if (!o.mp4_path.empty()) {
    if (png_pattern(o).empty()) throw Error("--mp4: the preview is made from PNG frames; add -o frames/%04d.png");
    if (find_ffmpeg().empty())
      throw Error(
          "--mp4: ffmpeg is not installed (on Debian: apt-get install ffmpeg); the frames need no ffmpeg, leave "
          "--mp4 out to render them alone");
    check_writable_destination(o.mp4_path);
  }
  if (!o.stats_path.empty()) check_writable_destination(o.stats_path);
  check_cache_files(job);
}

WalkthroughResult render_walkthrough(const WalkthroughRequest& o) {
  check_walkthrough(o);
  const RenderSettings& request = o.render.settings;
  const bool pre_pass = o.cache == CacheMode::pre_pass;
  WalkthroughResult result;
  // Along the glTF's own animation (no --keyframes, no --orbit) the walkthrough plays it: the loader's note that
  // `render` leaves animations unplayed would mislead.
  const Scene scene = load_scene(o.render, ScenePose{-1, 0.0, o.keyframes.empty() && !(o.orbit_seconds > 0.0)});
  const CameraPath path = choose_path(o, scene);
  const long long all_frames = (long long)std::floor(path.duration * o.fps + 1e-6) + 1;
  const long long first = o.first_frame, last = o.last_frame >= 0 ? o.last_frame : all_frames - 1;
  if (first < 0 || last < first) throw Error("--first-frame and --last-frame: an empty or negative range");
  if (last - first + 1 > kMaxFrames) throw Error("animate: at most " + std::to_string(kMaxFrames) + " frames a run");
  std::vector<FramePattern> outputs;
  for (const std::string& out : o.render.outputs) outputs.emplace_back(out, "-o");
  for (const FramePattern& p : outputs) check_writable_destination(p.path(first));
  if (pre_pass && (first + o.cache_every - 1) / o.cache_every * o.cache_every > last)
    throw Error("--cache-every " + std::to_string(o.cache_every) + ": no key frame (a frame it divides) in frames " +
                std::to_string(first) + " to " + std::to_string(last));
  const bool orthographic = scene.cameras[size_t(request.camera)].orthographic;
  result.scene = scene.source;
  result.path_description = path.description;
  result.path_duration = path.duration;
  result.first = first;
  result.last = last;

  DeviceInfo device = select_device(o.render.device);
  result.device = device.name;
  log_info("device: " + device.name + " (" + device.platform_name + ")");
  log_info("camera path: " + path.description + ", " + std::to_string(path.duration) + " s; frames " +
           std::to_string(first) + " to " + std::to_string(last) + " at " + std::to_string(o.fps) + " frames/s");
  const auto start = std::chrono::steady_clock::now();
  GpuContext gpu(device);
  gpu.set_memory_budget(o.render.limits.device_memory_bytes);
  FrameRenderers renderers(gpu, o, scene, path);
  renderers.check_poses(first, last);
  const ProgressHidden hidden;  // a line a frame instead of each pass's progress

  auto frame_settings = [&](long long frame) {
    RenderSettings settings = request;
    settings.keep_records = o.cache != CacheMode::per_frame;
    settings.color_only = outputs_need_only_color(o.render.outputs);
    CameraPose pose = path.at(double(frame) / o.fps);
    if (orthographic) pose.fov_degrees.reset();
    settings.camera_overrides = pose.overrides();
    return settings;
  };
  if (!o.render.cache_in.empty()) {  // before any frame: a file that does not fit is refused with no output
    load_cache_file(gpu, renderers.current(), scene, renderers.current().plan(frame_settings(first)),
                    o.render.cache_in, path.moves_scene_animation);
    // Records kept from a moving scene's file start where the file's time left them (a fixed cache: each frame).
    if (o.cache == CacheMode::kept) renderers.bring_records_to(first, renderers.current().kept_records().times);
  }
  if (o.cache == CacheMode::merge) {
    // The parts, each read as a stranger's cache file for these settings, merged (sequence/cache_merge.h), written.
    const FramePlan plan = renderers.current().plan(frame_settings(first));
    const size_t capacity = request.kept_records_capacity;
    std::vector<KeptCache> caches(o.cache_merge.size(), KeptCache(capacity));
    std::vector<CachePart> parts;
    for (size_t i = 0; i < caches.size(); ++i) {
      load_cache_file(gpu, caches[i], scene, plan, o.cache_merge[i], path.moves_scene_animation);
      parts.push_back({o.cache_merge[i], &caches[i]});
    }
    // A moving scene: an earlier key frame's record stands for a later one's only where it still holds there.
    std::optional<RecordMoves> moves = renderers.record_moves();
    HoldsAt holds;
    if (moves)
      holds = [&moves, fps = caches[0].times.fps](const CacheRecord& record, uint64_t from, uint64_t to) {
        return moves->holds(record, double(from) / fps, double(to) / fps);
      };
    KeptCache merged(capacity);
    result.merge = merge_cache_parts(parts, kept_records_key(plan.frame_settings()), capacity, merged, holds);
    save_cache_file(gpu, merged, scene, plan, o.render.cache_out);
    return result;
  }
  // A fixed cache: what the file holds, put back before every frame (a frame's own records go with it).
  std::optional<KeptCache> fixed_cache;
  if (o.cache == CacheMode::fixed) fixed_cache.emplace(renderers.current().kept_records());
  // A moving scene's merged cache: each frame takes the light of its key frame (the last at or before it; the first
  // before any), shot once a run of frames that share it (FrameRenderers::key_frame_light); the renderer's moves do
  // not make it again.
  std::vector<long long> key_frames;
  if (fixed_cache && renderers.animated() && fixed_cache->times.by_key_frame) {
    for (const KeptRecords* kind : {&fixed_cache->irradiance, &fixed_cache->radiance})
      key_frames.insert(key_frames.end(), kind->last_used().begin(), kind->last_used().end());
    std::sort(key_frames.begin(), key_frames.end());
    key_frames.erase(std::unique(key_frames.begin(), key_frames.end()), key_frames.end());
    renderers.current().hold_light(true);
  }
  std::optional<long long> light_key;
  KeptLight key_light;
  PrePassPart part(renderers.times(first, true));

  FramePlan last_plan;
  std::string table = kFrameTableHeader;
  for (long long frame = first; frame <= last; ++frame) {
    FrameRow row;
    row.frame = frame;
    row.time = double(frame) / o.fps;
    if (pre_pass && frame % o.cache_every != 0) continue;
    if (o.skip_existing && std::all_of(outputs.begin(), outputs.end(), [&](const FramePattern& p) {
          return std::filesystem::is_regular_file(p.path(frame));
        })) {
      ++result.skipped;
      continue;
    }
    const RenderSettings settings = frame_settings(frame);
    Renderer& renderer = renderers.for_frame(frame);
    RenderStats key_light_stats;
    if (!key_frames.empty()) {
      const auto after = std::upper_bound(key_frames.begin(), key_frames.end(), frame);
      const long long key = after == key_frames.begin() ? key_frames.front() : *(after - 1);
      if (light_key != key) {
        key_light = renderers.key_frame_light(key, frame, frame_settings(key), key_light_stats);
        light_key = key;
      }
    }
    if (fixed_cache) {
      renderer.kept_records() = *fixed_cache;
      if (light_key) renderer.kept_records().light = key_light;
      renderers.bring_records_to(frame, fixed_cache->times, fixed_cache->times.by_key_frame);
    }
    if (pre_pass) {  // a key frame starts from no records (a still scene's light stays, the same in every task)
      renderer.kept_records().irradiance.drop_records();
      renderer.kept_records().radiance.drop_records();
    }
    // A moving scene's key frame, or a frame of a fixed cache whose records hold one time, shoots its own light where
    // the scene stands at it, so that it depends on no frame before it (whichever task renders it).
    if ((pre_pass || (fixed_cache && !light_key)) && renderers.animated()) renderer.forget_light();
    last_plan = renderer.plan(settings);
    RenderedImage image = renderer.render(last_plan);
    image.stats.photon_map.seconds += key_light_stats.photon_map.seconds;
    image.stats.total_s += key_light_stats.total_s;
    if (o.cache == CacheMode::kept) renderers.look_ahead(frame, last, last_plan, image.stats);
    if (pre_pass) part.add_key_frame(frame, renderer.kept_records());
    ExrAttributes attributes = render_attributes(renderers.scene(), image, settings);
    attributes["rcsplat:frame"] = std::to_string(frame);
    attributes["rcsplat:time"] = std::to_string(row.time);
    for (const FramePattern& p : outputs) write_render(p.path(frame), image, o.render.exposure, attributes);
    row.stats = image.stats;
    result.width = image.width;
    result.height = image.height;
    row.host_peak_bytes = peak_host_bytes();
    result.rows.push_back(row);
    table += frame_table_row(row);
    if (!o.stats_path.empty()) write_text_file(o.stats_path, table);  // after each frame: a stopped run keeps its rows
    char line[200];
    std::snprintf(line, sizeof line, "frame %lld (%lld of %lld, t = %.3f s): %.2f s, %llu records (%llu reused, %llu kept)",
                  frame, frame - first + 1, last - first + 1, row.time, image.stats.total_s,
                  (unsigned long long)(image.stats.irradiance.records + image.stats.radiance.records),
                  (unsigned long long)image.stats.kept_records.reused,
                  (unsigned long long)image.stats.kept_records.kept);
    log_info(line);
    report_progress(double(frame - first + 1) / double(last - first + 1));
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (pre_pass) {
    const KeptCache written =
        part.cache(renderers.current().kept_records(), kept_records_key(last_plan.frame_settings()), request.kept_records_capacity);
    save_cache_file(gpu, written, scene, last_plan, o.render.cache_out);
    result.pre_pass_irradiance = part.irradiance_records();
    result.pre_pass_radiance = part.radiance_records();
  } else if (!o.render.cache_out.empty()) {
    KeptCache& kept = renderers.current().kept_records();
    if (renderers.animated()) {  // the records as they hold at the last frame, with its time
      kept.irradiance.settle_for_file();
      kept.radiance.settle_for_file();
      kept.times = renderers.times(last, false);
    }
    save_cache_file(gpu, kept, scene, last_plan, o.render.cache_out);
  }
  if (!o.mp4_path.empty()) {
    encode_mp4(find_ffmpeg(), png_pattern(o), first, last - first + 1, o.fps, o.mp4_path);
    result.mp4_written = true;
  }
  return result;
}

}  // namespace rcsplat
