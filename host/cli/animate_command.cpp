// `rcsplat animate`: a camera path rendered frame by frame by one Renderer (the BVH, programs, photon map and light
// guide are made once; each frame places its own records), each frame written as soon as it is done, with a row of
// statistics a frame and, where ffmpeg is installed, an MP4 preview.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cl/device_info.h"
#include "cli/command_line.h"
#include "cli/commands.h"
#include "render/cache_merge.h"
#include "render/camera_path.h"
#include "render/kept_records.h"
#include "render/render_output.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/frame_pattern.h"
#include "util/log.h"
#include "util/memory_use.h"
#include "util/paths.h"

extern char** environ;

namespace rcsplat {
namespace {

constexpr long long kMaxFrames = 1000000;

// The path of `program` found on PATH, or "".
std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::string candidate = dir + "/" + program;
    if (access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return "";
}

// Runs a program with these arguments (no shell: the names are the user's), waits; its exit status, -1 if not run.
int run_program(const std::string& program, const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

CameraPath choose_path(const AnimateOptions& o, const Scene& scene) {
  const bool overrides = o.render.settings.camera_overrides.eye || o.render.settings.camera_overrides.target ||
                         o.render.settings.camera_overrides.up || o.render.settings.camera_overrides.fov_degrees;
  if (!o.keyframes.empty() && o.orbit_seconds > 0.0) throw Error("animate: give --keyframes or --orbit, not both");
  if (o.orbit_seconds > 0.0)
    return orbit_camera_path(choose_camera(scene, o.render.settings.camera, o.render.settings.camera_overrides),
                             o.orbit_seconds, o.orbit_degrees);
  if (overrides)
    throw Error(
        "animate: --eye, --target, --up and --fov set where an --orbit starts; a keyframe file or the scene's "
        "animation places the camera itself");
  if (!o.keyframes.empty()) return read_keyframe_camera_path(o.keyframes);
  if (o.render.scene_path.empty())
    throw Error("animate: the built-in Cornell box has no animation; give --orbit SECONDS or --keyframes FILE");
  return gltf_camera_path(scene, o.render.settings.camera, o.animation, o.cache_per_frame);
}

struct FrameRow {
  long long frame = 0;
  double time = 0.0;
  RenderStats stats;
  size_t host_peak_bytes = 0;
};

const char* kCsvHeader =
    "frame,time_s,seconds,kernel_build_s,bvh_s,upload_s,probe_s,gbuffer_s,direct_s,photons_s,caustics_s,guide_s,"
    "records_s,placement_s,splat_s,radiance_s,resolve_s,glossy_s,path_s,layers_s,records,records_reused,"
    "records_added,records_evicted,radiance_records,radiance_reused,radiance_added,radiance_evicted,primary_rays,"
    "shadow_rays,record_rays,radiance_rays,glossy_rays,"
    "path_rays,device_peak_bytes,host_peak_bytes\n";

std::string csv_row(const FrameRow& r) {
  const RenderStats& s = r.stats;
  std::ostringstream out;
  out.precision(6);
  out << r.frame << ',' << r.time << ',' << s.total_s << ',' << s.program_s;
  for (const RenderStats::StageTime& stage : s.stage_times()) out << ',' << stage.seconds;
  const KeptRecordsStats& k = s.kept_records;
  const bool kept = k.capacity > 0;  // else a cache per frame: every record is new, none is kept
  out << ',' << s.irradiance.records << ',' << k.reused << ',' << (kept ? k.added : s.irradiance.records) << ','
      << k.evicted << ',' << s.radiance.records << ',' << s.kept_radiance_records.reused << ','
      << (kept ? s.kept_radiance_records.added : s.radiance.records) << ',' << s.kept_radiance_records.evicted << ','
      << s.primary.primary_rays << ',' << s.primary.shadow_rays << ','
      << s.irradiance.rays << ',' << s.radiance.rays << ',' << s.glossy.rays << ',' << s.path.rays << ','
      << s.device_memory.peak_bytes << ',' << r.host_peak_bytes << '\n';
  return out.str();
}

// One kind of records in a frame: those it splatted, and of them the kept ones it reused and those it added; with a
// cache per frame (no capacity) every record is added.
nlohmann::json kept_json(const KeptRecordsStats& k, uint64_t records) {
  const bool kept = k.capacity > 0;
  return {{"records", records},
          {"reused", k.reused},
          {"added", kept ? k.added : records},
          {"evicted", k.evicted},
          {"kept", k.kept}};
}

nlohmann::json frame_json(const FrameRow& r) {
  const RenderStats& s = r.stats;
  nlohmann::json seconds = {{"total", s.total_s}, {"kernel_build", s.program_s}};
  for (const RenderStats::StageTime& stage : s.stage_times()) seconds[stage.name] = stage.seconds;
  return {{"frame", r.frame},
          {"time", r.time},
          {"seconds", seconds},
          {"records",
           {{"irradiance", kept_json(s.kept_records, s.irradiance.records)},
            {"radiance", kept_json(s.kept_radiance_records, s.radiance.records)}}},
          {"rays",
           {{"primary", s.primary.primary_rays},
            {"shadow", s.primary.shadow_rays},
            {"records", s.irradiance.rays},
            {"radiance", s.radiance.rays},
            {"glossy", s.glossy.rays},
            {"path", s.path.rays}}},
          {"memory", {{"device_peak_bytes", s.device_memory.peak_bytes}, {"host_peak_bytes", r.host_peak_bytes}}}};
}

// The cache modes that may go together: a pre-pass, a merge, a fixed cache, a cache per frame, reruns.
void check_cache_modes(const AnimateOptions& o) {
  const bool pre_pass = o.cache_every > 0, merging = !o.cache_merge.empty();
  if ((!o.render.cache_in.empty() || !o.render.cache_out.empty()) && o.cache_per_frame)
    throw Error("--cache-in and --cache-out: with --cache-per-frame no record is kept to read or write");
  if (o.cache_fixed && o.render.cache_in.empty())
    throw Error("--cache-fixed: needs --cache-in, the cache file every frame starts from");
  if (o.skip_existing && !o.cache_fixed && !o.cache_per_frame)
    throw Error("--skip-existing: without --cache-fixed or --cache-per-frame each frame reads the records the frames "
                "before it placed, so a frame rendered after a skipped one would differ from a whole run's");
  if (o.cache_fixed && !o.render.cache_out.empty())
    throw Error("--cache-fixed and --cache-out: a fixed cache keeps nothing a frame places, so there is nothing new to "
                "write");
  if (o.cache_every < 0) throw Error("--cache-every: a key frame every K frames needs K >= 1");
  if (pre_pass || merging) {
    const char* mode = pre_pass ? "--cache-every" : "--cache-merge";
    if (pre_pass && merging) throw Error("--cache-every and --cache-merge: a pre-pass task or a merge, not both");
    if (o.render.cache_out.empty()) throw Error(std::string(mode) + ": needs --cache-out, the file it writes");
    if (!o.render.cache_in.empty() || o.cache_per_frame || o.skip_existing)
      throw Error(std::string(mode) +
                  ": a pre-pass starts each key frame from no records; leave out --cache-in, --cache-fixed, "
                  "--cache-per-frame and --skip-existing");
    if (!o.mp4_path.empty()) throw Error(std::string(mode) + ": renders the key frames only; leave out --mp4");
    if (merging && !o.render.outputs.empty()) throw Error("--cache-merge: renders no frame; leave out -o");
    if (merging && !o.stats_path.empty()) throw Error("--cache-merge: renders no frame; leave out --stats");
  }
}

// What a pre-pass task writes: each key frame's records, in the order its frame placed them, tagged with the frame.
struct PrePassPart {
  KeptRecords::Contents irradiance, radiance;
  uint64_t frames = 0;

  void add_key_frame(long long frame, const KeptCache& kept) {
    for (auto [from, to] : {std::pair{&kept.irradiance, &irradiance}, std::pair{&kept.radiance, &radiance}}) {
      if (from->stats().evicted)
        throw Error("--cache-every: key frame " + std::to_string(frame) + " placed more records than --kept-records " +
                    "keeps; give a larger --kept-records here, to the merge and to every animate that reads the file");
      to->records.insert(to->records.end(), from->records().begin(), from->records().end());
      to->last_used.insert(to->last_used.end(), from->records().size(), uint64_t(frame));
      to->payload.insert(to->payload.end(), from->payload().begin(), from->payload().end());
      if (!from->records().empty()) to->payload_per_record = from->payload_per_record();
      to->largest_radiance = std::max(to->largest_radiance, from->largest_radiance());
    }
    frames = uint64_t(frame) + 1;
  }

  // The part as a cache file holds it, with the light the key frames read.
  KeptCache cache(const KeptCache& kept, const KeptRecordsKey& key, size_t capacity) const {
    if (irradiance.records.size() > capacity || radiance.records.size() > capacity)
      throw Error("--cache-every: the key frames placed " +
                  std::to_string(std::max(irradiance.records.size(), radiance.records.size())) +
                  " records, more than --kept-records " + std::to_string(capacity) +
                  "; give a larger --kept-records here, to the merge and to every animate that reads the file");
    KeptCache out(capacity);
    out.irradiance.restore(key, irradiance, frames);
    out.radiance.restore(key, radiance, frames);
    out.light = kept.light;
    return out;
  }
};

// `animate --cache-merge PART... --cache-out FILE`: the parts, each read as a stranger's cache file for these settings,
// merged (render/cache_merge.h) and written.
int merge_parts(const AnimateOptions& o, const GpuContext& gpu, const Scene& scene, const FramePlan& plan) {
  std::vector<KeptCache> caches(o.cache_merge.size(), KeptCache(o.render.settings.kept_records_capacity));
  std::vector<CachePart> parts;
  for (size_t i = 0; i < caches.size(); ++i) {
    load_cache_file(gpu, caches[i], scene, plan, o.cache_merge[i]);
    parts.push_back({o.cache_merge[i], &caches[i]});
  }
  KeptCache merged(o.render.settings.kept_records_capacity);
  const CacheMergeStats stats = merge_cache_parts(parts, kept_records_key(plan.frame), o.render.settings.kept_records_capacity, merged);
  save_cache_file(gpu, merged, scene, plan, o.render.cache_out);
  std::printf("merged       %zu parts, %zu key frames: irradiance records %zu of %zu kept, radiance records %zu of %zu "
              "(a record no earlier key frame's records reach is kept)\n",
              parts.size(), stats.key_frames, stats.irradiance_kept, stats.irradiance_in, stats.radiance_kept,
              stats.radiance_in);
  std::printf("wrote        %s\n", o.render.cache_out.c_str());
  if (!o.render.json_path.empty())
    write_text_file(o.render.json_path,
                    nlohmann::json{{"parts", o.cache_merge},
                                   {"key_frames", stats.key_frames},
                                   {"irradiance_records", {{"in", stats.irradiance_in}, {"kept", stats.irradiance_kept}}},
                                   {"radiance_records", {{"in", stats.radiance_in}, {"kept", stats.radiance_kept}}},
                                   {"cache_out", o.render.cache_out}}
                            .dump(2) + "\n");
  return 0;
}

}  // namespace

int run_animate(const AnimateOptions& o) {
  set_progress_lines(o.render.progress_lines);
  const RenderSettings& request = o.render.settings;
  check_request(request);
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) throw Error("--fps must be above 0 and at most 1000");
  const bool pre_pass = o.cache_every > 0, merging = !o.cache_merge.empty();
  check_cache_modes(o);
  if (o.render.outputs.empty() && !pre_pass && !merging)
    throw Error("animate: give at least one output with -o frames/%04d.exr");
  std::vector<FramePattern> outputs;
  for (const std::string& out : o.render.outputs) {
    outputs.emplace_back(out, "-o");
    if (!is_output_format(out)) throw Error(out + ": unknown output format (use " + output_formats() + ")");
  }
  std::string ffmpeg, png_pattern;
  if (!o.mp4_path.empty()) {
    for (const FramePattern& p : outputs)
      if (png_pattern.empty() && lower_extension(p.pattern()) == ".png") png_pattern = p.pattern();
    if (png_pattern.empty()) throw Error("--mp4: the preview is made from PNG frames; add -o frames/%04d.png");
    ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty())
      throw Error(
          "--mp4: ffmpeg is not installed (on Debian: apt-get install ffmpeg); the frames need no ffmpeg, "
          "leave --mp4 out to render them alone");
    check_writable_destination(o.mp4_path);
  }
  for (const std::string& path : {o.stats_path, o.render.json_path})
    if (!path.empty()) check_writable_destination(path);
  check_cache_files(o.render);
  Scene scene =
      load_scene(o.render.scene_path, request.camera, request.camera_overrides, o.render.environment, o.render.limits);
  const CameraPath path = choose_path(o, scene);
  const long long all_frames = (long long)std::floor(path.duration * o.fps + 1e-6) + 1;
  const long long first = o.first_frame, last = o.last_frame >= 0 ? o.last_frame : all_frames - 1;
  if (first < 0 || last < first) throw Error("--first-frame and --last-frame: an empty or negative range");
  if (last - first + 1 > kMaxFrames) throw Error("animate: at most 1000000 frames a run");
  for (const FramePattern& p : outputs) check_writable_destination(p.path(first));
  if (pre_pass && (first + o.cache_every - 1) / o.cache_every * o.cache_every > last)
    throw Error("--cache-every " + std::to_string(o.cache_every) + ": no key frame (a frame it divides) in frames " +
                std::to_string(first) + " to " + std::to_string(last));
  const bool orthographic = scene.cameras[size_t(request.camera)].orthographic;

  DeviceInfo device = select_device(o.render.device);
  log_info("device: " + device.name + " (" + device.platform_name + ")");
  log_info("camera path: " + path.description + ", " + std::to_string(path.duration) + " s; frames " +
           std::to_string(first) + " to " + std::to_string(last) + " at " + std::to_string(o.fps) + " frames/s");
  const auto start = std::chrono::steady_clock::now();
  GpuContext gpu(device);
  gpu.set_memory_budget(o.render.limits.device_memory_bytes);
  // A scene the path's animation moves (--cache-per-frame only: choose_path refused it otherwise) is loaded again in
  // each frame's pose with a renderer of its own, as `render` would render that pose; a still scene has one renderer.
  const bool scene_moves = path.moves_scene_animation >= 0;
  std::unique_ptr<Scene> posed_scene;
  std::unique_ptr<Renderer> renderer_holder =
      scene_moves ? nullptr : std::make_unique<Renderer>(gpu, scene, request.forced_switches);
  auto pose_scene = [&](long long frame) -> Renderer& {
    if (!scene_moves) return *renderer_holder;
    renderer_holder.reset();  // before the scene it renders from
    posed_scene = std::make_unique<Scene>(load_scene(o.render.scene_path, request.camera, request.camera_overrides,
                                                     o.render.environment, o.render.limits,
                                                     ScenePose{path.moves_scene_animation, double(frame) / o.fps}));
    renderer_holder = std::make_unique<Renderer>(gpu, *posed_scene, request.forced_switches);
    return *renderer_holder;
  };
  set_progress_shown(false);  // a line a frame instead of each pass's progress
  struct ShowProgressAgain {
    ~ShowProgressAgain() { set_progress_shown(true); }
  } show_progress_again;

  FramePlan last_plan;
  auto frame_settings = [&](long long frame) {
    RenderSettings settings = request;
    settings.keep_records = !o.cache_per_frame;
    settings.color_only = outputs_need_only_color(o.render.outputs);
    CameraPose pose = path.at(double(frame) / o.fps);
    if (orthographic) pose.fov_degrees.reset();
    settings.camera_overrides = pose.overrides();
    return settings;
  };
  if (!o.render.cache_in.empty())  // before any frame: a file that does not fit is refused with no output
    load_cache_file(gpu, *renderer_holder, scene, renderer_holder->plan(frame_settings(first)), o.render.cache_in);
  // A fixed cache: what the file holds, put back before every frame (a frame's own records go with it).
  std::optional<KeptCache> fixed_cache;
  if (o.cache_fixed) fixed_cache.emplace(renderer_holder->kept_records());
  if (merging) return merge_parts(o, gpu, scene, renderer_holder->plan(frame_settings(first)));
  PrePassPart part;

  std::vector<FrameRow> rows;
  long long skipped = 0;
  int width = 0, height = 0;
  std::string csv = kCsvHeader;
  for (long long frame = first; frame <= last; ++frame) {
    FrameRow row;
    row.frame = frame;
    row.time = double(frame) / o.fps;
    if (pre_pass && frame % o.cache_every != 0) continue;
    if (o.skip_existing && std::all_of(outputs.begin(), outputs.end(), [&](const FramePattern& p) {
          return std::filesystem::is_regular_file(p.path(frame));
        })) {
      ++skipped;
      continue;
    }
    const RenderSettings settings = frame_settings(frame);
    Renderer& frame_renderer = pose_scene(frame);
    if (fixed_cache) frame_renderer.kept_records() = *fixed_cache;
    if (pre_pass) {  // a key frame starts from no records; the light stays, the same in every task
      frame_renderer.kept_records().irradiance.drop_records();
      frame_renderer.kept_records().radiance.drop_records();
    }
    last_plan = frame_renderer.plan(settings);
    const RenderedImage image = frame_renderer.render(last_plan);
    if (pre_pass) part.add_key_frame(frame, frame_renderer.kept_records());
    ExrAttributes attributes = render_attributes(posed_scene ? *posed_scene : scene, image, settings);
    attributes["rcsplat:frame"] = std::to_string(frame);
    attributes["rcsplat:time"] = std::to_string(row.time);
    for (const FramePattern& p : outputs) write_render(p.path(frame), image, o.render.exposure, attributes);
    row.stats = image.stats;
    width = image.width;
    height = image.height;
    row.host_peak_bytes = peak_host_bytes();
    rows.push_back(row);
    csv += csv_row(row);
    if (!o.stats_path.empty()) write_text_file(o.stats_path, csv);  // after each frame: a stopped run keeps its rows
    char line[200];
    std::snprintf(line, sizeof line,
                  "frame %lld (%lld of %lld, t = %.3f s): %.2f s, %llu records (%llu reused, "
                  "%llu kept)",
                  frame, frame - first + 1, last - first + 1, row.time, image.stats.total_s,
                  (unsigned long long)(image.stats.irradiance.records + image.stats.radiance.records),
                  (unsigned long long)image.stats.kept_records.reused,
                  (unsigned long long)image.stats.kept_records.kept);
    log_info(line);
    report_progress(double(frame - first + 1) / double(last - first + 1));
  }
  report_progress(1.0);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (pre_pass) {
    const KeptCache written = part.cache(renderer_holder->kept_records(), kept_records_key(last_plan.frame), o.render.settings.kept_records_capacity);
    save_cache_file(gpu, written, scene, last_plan, o.render.cache_out);
  } else if (!o.render.cache_out.empty()) {
    save_cache_file(gpu, *renderer_holder, scene, last_plan, o.render.cache_out);
  }
  bool mp4_written = false;
  if (!ffmpeg.empty()) {
    // Written beside the target and renamed, as every output is (util/atomic_file.h).
    write_file_atomically(o.mp4_path, [&](const std::string& temp) -> std::string {
      char rate[32];
      std::snprintf(rate, sizeof rate, "%.9g", o.fps);
      const int status = run_program(ffmpeg, {"-y",
                                              "-loglevel",
                                              "error",
                                              "-framerate",
                                              rate,
                                              "-start_number",
                                              std::to_string(first),
                                              "-i",
                                              png_pattern,
                                              "-frames:v",
                                              std::to_string(last - first + 1),
                                              "-c:v",
                                              "libx264",
                                              "-pix_fmt",
                                              "yuv420p",
                                              "-vf",
                                              "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                              "-f",
                                              "mp4",
                                              temp});
      return status == 0 ? "" : "ffmpeg failed (exit status " + std::to_string(status) + ")";
    });
    mp4_written = true;
  }

  // The JSON summary, the same keys whether or not any frame was rendered (with --skip-existing, maybe none).
  auto write_json = [&](const nlohmann::json& seconds) {
    if (o.render.json_path.empty()) return;
    nlohmann::json frames = nlohmann::json::array();
    for (const FrameRow& r : rows) frames.push_back(frame_json(r));
    nlohmann::json outputs_json = o.render.outputs;
    if (mp4_written) outputs_json.push_back(o.mp4_path);
    const nlohmann::json j = {
        {"scene", scene.source},
        {"camera_path", {{"source", path.description}, {"duration", path.duration}}},
        {"device", gpu.device_info().name},
        {"fps", o.fps},
        {"first_frame", first},
        {"last_frame", last},
        {"cache", o.cache_per_frame ? "per_frame" : o.cache_fixed ? "fixed" : pre_pass ? "pre_pass" : "kept_records"},
        {"kept_records_capacity", o.render.settings.kept_records_capacity},
        {"skipped_frames", skipped},
        {"seconds", seconds},
        {"frames", frames},
        {"outputs", outputs_json}};
    write_text_file(o.render.json_path, j.dump(2) + "\n");
  };
  if (skipped) std::printf("skipped      %lld frames whose files were there already (--skip-existing)\n", skipped);
  if (rows.empty()) {
    std::printf("frames       %lld to %lld: none rendered\n", first, last);
    if (mp4_written) std::printf("wrote        %s\n", o.mp4_path.c_str());
    write_json({{"wall", wall}});
    return 0;
  }
  // The summary: the first frame pays for the setup (BVH, upload, kernel builds); later frames show the steady cost.
  double later = 0.0;
  for (size_t i = 1; i < rows.size(); ++i) later += rows[i].stats.total_s;
  const double later_mean = rows.size() > 1 ? later / double(rows.size() - 1) : 0.0;
  std::printf("scene        %s\n", scene.source.c_str());
  std::printf("camera path  %s, %.3f s\n", path.description.c_str(), path.duration);
  std::printf("device       %s\n", gpu.device_info().name.c_str());
  std::printf("frames       %lld to %lld at %g frames/s, %d x %d, indirect light: %s\n", first, last, o.fps, width,
              height, gi_method_name(rows.front().stats.gi));
  const GiMethod gi = rows.front().stats.gi;
  if (gi == GiMethod::octree || (gi == GiMethod::splat && o.cache_per_frame)) {
    std::printf("cache        a new cache each frame%s\n",
                o.cache_per_frame ? " (--cache-per-frame)" : " (records are kept by the splat only)");
  } else if (gi == GiMethod::splat) {
    auto summary = [&](const char* kind, KeptRecordsStats RenderStats::*member) {
      uint64_t reused = 0, added = 0, evicted = 0;
      for (const FrameRow& r : rows) {
        reused += (r.stats.*member).reused;
        added += (r.stats.*member).added;
        evicted += (r.stats.*member).evicted;
      }
      std::printf(
          "cache        %s records kept across frames: %llu placed, %llu reused in all (%.0f a frame), %llu "
          "evicted, %llu kept at the end (at most %zu: --kept-records)\n",
          kind, (unsigned long long)added, (unsigned long long)reused, double(reused) / double(rows.size()),
          (unsigned long long)evicted, (unsigned long long)(rows.back().stats.*member).kept, o.render.settings.kept_records_capacity);
    };
    if (pre_pass) {
      std::printf("cache        pre-pass: %zu key frames (one every %lld frames), each from no records: %zu irradiance and "
                  "%zu radiance records tagged by key frame, for --cache-merge\n",
                  rows.size(), o.cache_every, part.irradiance.records.size(), part.radiance.records.size());
    } else {
      if (o.cache_fixed)
        std::printf("cache        fixed: every frame from %s's records (--cache-fixed)\n", o.render.cache_in.c_str());
      summary("irradiance", &RenderStats::kept_records);
      if (rows.front().stats.radiance.records) summary("radiance", &RenderStats::kept_radiance_records);
    }
  }
  std::printf("time         %.2f s in all; first frame %.2f s (with the setup), later frames %.2f s each on average\n",
              wall, rows.front().stats.total_s, later_mean);
  for (const FramePattern& p : outputs) std::printf("wrote        %s\n", p.pattern().c_str());
  if (mp4_written) std::printf("wrote        %s\n", o.mp4_path.c_str());
  if (!o.render.cache_out.empty()) std::printf("wrote        %s\n", o.render.cache_out.c_str());
  if (!o.stats_path.empty()) std::printf("wrote        %s\n", o.stats_path.c_str());
  write_json({{"wall", wall}, {"first_frame", rows.front().stats.total_s}, {"later_frames_mean", later_mean}});
  return 0;
}

Command add_animate_command(CLI::App& app, const HelpGroups& groups) {
  struct State {
    AnimateOptions options;
    CameraFlags camera;
    EnvironmentFlags environment;
    RenderMethodFlags method;
  };
  auto s = std::make_shared<State>();
  AnimateOptions& o = s->options;
  const AnimateOptions defaults;
  CLI::App* cmd = app.add_subcommand(
      "animate",
      "Render a camera path to a frame sequence: the scene's glTF camera animation, a keyframe file or an orbit "
      "(default scene: the built-in Cornell box, which needs --orbit or --keyframes)");
  add_frame_options(cmd, o.render, s->camera, s->environment, groups);
  // A cache pre-pass or merge may render no image: run_animate asks for -o where frames are written.
  cmd->get_option("--output")->required(false);
  s->method.add(cmd, o.render, groups);
  cmd->add_option("--keyframes", o.keyframes,
                  "Camera path from a keyframe file: a line a key, \"time ex ey ez tx ty tz ux uy uz fov\" "
                  "(docs/USAGE.md)");
  cmd->add_option("--orbit", o.orbit_seconds,
                  "Camera path: one turn around the camera's target in this many seconds (--eye, --target and --up "
                  "set where it starts)");
  cmd->add_option("--orbit-degrees", o.orbit_degrees,
                  "--orbit: the arc swept in its seconds, in degrees (default " + shortest(float(defaults.orbit_degrees)) +
                      ": a whole turn; negative: clockwise seen from above)");
  cmd->add_option("--animation", o.animation,
                  "Without --keyframes or --orbit: the scene's glTF animation that moves --camera (default " +
                      std::to_string(defaults.animation) + ")")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--fps", o.fps, "Frames a second of the path's time (default " + shortest(float(defaults.fps)) + ")");
  cmd->add_option("--first-frame", o.first_frame, "First frame rendered (default 0)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--last-frame", o.last_frame, "Last frame rendered (default: the path's end)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--cache-per-frame", o.cache_per_frame,
                "Place every frame's records anew, as `render` does (the default keeps the irradiance records across "
                "frames and places new ones only where none reaches)");
  cmd->add_flag("--cache-fixed", o.cache_fixed,
                "With --cache-in: every frame starts from the file's records alone (what a frame places is not kept "
                "for the next), so a frame is the same bits whatever range of frames a process renders: a "
                "walkthrough split over processes or machines (docs/USAGE.md, \"Cache files\")");
  cmd->add_flag("--skip-existing", o.skip_existing,
                "Render only the frames whose output files are not all there already: a rerun or requeue of a "
                "stopped task (outputs are written whole or not at all); needs --cache-fixed or --cache-per-frame, "
                "so that no frame depends on the frames before it");
  cmd->add_option("--cache-every", o.cache_every,
                  "The cache pre-pass of a walkthrough split over tasks: render only the range's frames that K "
                  "divides (key frames), each from no records, and write their records, tagged by key frame, to "
                  "--cache-out (-o optional); merge the tasks' files with --cache-merge (docs/FARM.md)")
      ->check(CLI::Range(1LL, 1000000LL));
  cmd->add_option("--cache-merge", o.cache_merge,
                  "Merge these --cache-every files into --cache-out and render nothing: the same records in the same "
                  "order whatever the split, a record dropped where an earlier key frame's records reach it "
                  "(docs/FARM.md)")
      ->expected(1, -1);
  cmd->add_option("--kept-records", o.render.settings.kept_records_capacity,
                  "Most irradiance records kept across frames; the least recently used go first (default " +
                      std::to_string(RenderSettings{}.kept_records_capacity) + ", " +
                      std::to_string(sizeof(CacheRecord)) + " bytes each)")
      ->check(CLI::Range(size_t(1), size_t(1) << 28));
  cmd->add_option("--stats", o.stats_path,
                  "Also write a CSV row a frame: time per pass, records, rays, device and host memory");
  cmd->add_option("--mp4", o.mp4_path,
                  "Also write an MP4 preview of the PNG frames with ffmpeg (H.264; needs ffmpeg installed)");
  return {cmd, [s, cmd] {
            s->camera.apply(s->options.render.settings);
            s->environment.apply(s->options.render.environment);
            s->method.apply(cmd, s->options.render);
            return run_animate(s->options);
          }};
}

}  // namespace rcsplat
