// `rcsplat animate`: the walkthrough library (sequence/walkthrough.h) run from the command line, with its summary
// printed and written as JSON.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "render/kept_records.h"
#include "util/atomic_file.h"
#include "util/log.h"

namespace rcsplat {
namespace {

// One kind of records in a frame: those it splatted, and of them the kept ones it reused and those it added; with a
// cache per frame (no capacity) every record is added.
nlohmann::json kept_json(const KeptRecordsStats& k, uint64_t records) {
  const bool kept = k.capacity > 0;
  return {{"records", records},
          {"reused", k.reused},
          {"added", kept ? k.added : records},
          {"evicted", k.evicted},
          {"moved", k.moved},
          {"ahead", k.ahead},
          {"windows", k.windows},
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

// `animate --cache-merge`: what was merged.
void print_merge(const AnimateOptions& options, const WalkthroughResult& result) {
  const WalkthroughRequest& o = options.walk;
  const CacheMergeStats& m = result.merge;
  std::printf("merged       %zu parts, %zu key frames: irradiance records %zu of %zu kept, radiance records %zu of %zu "
              "(a record no earlier key frame's records reach is kept)\n",
              o.cache_merge.size(), m.key_frames, m.irradiance_kept, m.irradiance_in, m.radiance_kept, m.radiance_in);
  std::printf("wrote        %s\n", o.render.cache_out.c_str());
  if (!options.json_path.empty())
    write_text_file(options.json_path,
                    nlohmann::json{{"parts", o.cache_merge},
                                   {"key_frames", m.key_frames},
                                   {"irradiance_records", {{"in", m.irradiance_in}, {"kept", m.irradiance_kept}}},
                                   {"radiance_records", {{"in", m.radiance_in}, {"kept", m.radiance_kept}}},
                                   {"cache_out", o.render.cache_out}}
                            .dump(2) + "\n");
}

}  // namespace

int run_animate(const AnimateOptions& options) {
  set_progress_lines(options.progress_lines);
  const WalkthroughRequest& o = options.walk;
  // The command's own output, before any work; render_walkthrough checks the request itself (check_walkthrough).
  if (!options.json_path.empty()) check_writable_destination(options.json_path);
  const WalkthroughResult result = render_walkthrough(o);
  report_progress(1.0);
  if (o.cache == CacheMode::merge) {
    print_merge(options, result);
    return 0;
  }
  const std::vector<FrameRow>& rows = result.rows;
  const long long first = result.first, last = result.last;

  // The JSON summary, the same keys whether or not any frame was rendered (with --skip-existing, maybe none).
  auto write_json = [&](const nlohmann::json& seconds) {
    if (options.json_path.empty()) return;
    nlohmann::json frames = nlohmann::json::array();
    for (const FrameRow& r : rows) frames.push_back(frame_json(r));
    nlohmann::json outputs_json = o.render.outputs;
    if (result.mp4_written) outputs_json.push_back(o.mp4_path);
    const nlohmann::json j = {
        {"scene", result.scene},
        {"camera_path", {{"source", result.path_description}, {"duration", result.path_duration}}},
        {"device", result.device},
        {"fps", o.fps},
        {"first_frame", first},
        {"last_frame", last},
        {"cache", cache_mode_name(o.cache)},
        {"kept_records_capacity", o.render.settings.kept_records_capacity},
        {"skipped_frames", result.skipped},
        {"seconds", seconds},
        {"frames", frames},
        {"outputs", outputs_json}};
    write_text_file(options.json_path, j.dump(2) + "\n");
  };
  if (result.skipped) std::printf("skipped      %lld frames whose files were there already (--skip-existing)\n", result.skipped);
  if (rows.empty()) {
    std::printf("frames       %lld to %lld: none rendered\n", first, last);
    if (result.mp4_written) std::printf("wrote        %s\n", o.mp4_path.c_str());
    write_json({{"wall", result.wall_s}});
    return 0;
  }
  // The summary: the first frame pays for the setup (BVH, upload, kernel builds); later frames show the steady cost.
  double later = 0.0;
  for (size_t i = 1; i < rows.size(); ++i) later += rows[i].stats.total_s;
  const double later_mean = rows.size() > 1 ? later / double(rows.size() - 1) : 0.0;
  std::printf("scene        %s\n", result.scene.c_str());
  std::printf("camera path  %s, %.3f s\n", result.path_description.c_str(), result.path_duration);
  std::printf("device       %s\n", result.device.c_str());
  std::printf("frames       %lld to %lld at %g frames/s, %d x %d, indirect light: %s\n", first, last, o.fps,
              result.width, result.height, gi_method_name(rows.front().stats.gi));
  const GiMethod gi = rows.front().stats.gi;
  const bool per_frame = o.cache == CacheMode::per_frame;
  if (gi == GiMethod::octree || (gi == GiMethod::splat && per_frame)) {
    std::printf("cache        a new cache each frame%s\n",
                per_frame ? " (--cache-per-frame)" : " (records are kept by the splat only)");
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
    if (o.cache == CacheMode::pre_pass) {
      std::printf("cache        pre-pass: %zu key frames (one every %lld frames), each from no records: %llu "
                  "irradiance and %llu radiance records tagged by key frame, for --cache-merge\n",
                  rows.size(), o.cache_every, (unsigned long long)result.pre_pass_irradiance,
                  (unsigned long long)result.pre_pass_radiance);
    } else {
      if (o.cache == CacheMode::fixed)
        std::printf("cache        fixed: every frame from %s's records (--cache-fixed)\n", o.render.cache_in.c_str());
      summary("irradiance", &RenderStats::kept_records);
      if (rows.front().stats.radiance.records) summary("radiance", &RenderStats::kept_radiance_records);
    }
  }
  std::printf("time         %.2f s in all; first frame %.2f s (with the setup), later frames %.2f s each on average\n",
              result.wall_s, rows.front().stats.total_s, later_mean);
  for (const std::string& p : o.render.outputs) std::printf("wrote        %s\n", p.c_str());
  if (result.mp4_written) std::printf("wrote        %s\n", o.mp4_path.c_str());
  if (!o.render.cache_out.empty()) std::printf("wrote        %s\n", o.render.cache_out.c_str());
  if (!o.stats_path.empty()) std::printf("wrote        %s\n", o.stats_path.c_str());
  write_json({{"wall", result.wall_s}, {"first_frame", rows.front().stats.total_s}, {"later_frames_mean", later_mean}});
  return 0;
}

Command add_animate_command(CLI::App& app, const HelpGroups& groups) {
  struct State {
    AnimateOptions options;
    CameraFlags camera;
    EnvironmentFlags environment;
    RenderMethodFlags method;
    bool per_frame = false, fixed = false;
  };
  auto s = std::make_shared<State>();
  WalkthroughRequest& o = s->options.walk;
  const WalkthroughRequest defaults;
  CLI::App* cmd = app.add_subcommand(
      "animate",
      "Render a camera path to a frame sequence: the scene's glTF camera animation, a keyframe file or an orbit "
      "(default scene: the built-in Cornell box, which needs --orbit or --keyframes)");
  add_frame_options(cmd, o.render, s->options.json_path, s->options.progress_lines, s->camera, s->environment,
                    groups);
  // A cache pre-pass or merge may render no image: run_animate asks for -o where frames are written.
  cmd->get_option("--output")->required(false);
  s->method.add(cmd, o.render, s->options.quality, groups);
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
  cmd->add_flag("--cache-per-frame", s->per_frame,
                "Place every frame's records anew, as `render` does (the default keeps the irradiance records across "
                "frames and places new ones only where none reaches)");
  cmd->add_flag("--cache-fixed", s->fixed,
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
  cmd->add_option("--moved-record-tolerance", o.moved_record_tolerance,
                  "Records kept through a moving scene: a move marks, to be computed again where they stand, the "
                  "records whose light it may have changed by more than this fraction (the moving part's share of the "
                  "record's hemisphere; default " + shortest(float(defaults.moved_record_tolerance)) +
                      "; those beside the part go and are placed again; a light that moves marks all)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--temporal-window", o.temporal_window,
                  "Records kept through a moving scene: a record a move marks is computed at its frame and at this "
                  "many frames later, and the frames between interpolate its light (1: computed at each frame its "
                  "marks ask; default " + std::to_string(defaults.temporal_window) + ")")
      ->check(CLI::Range(1LL, 240LL));
  cmd->add_option("--max-lag", o.max_lag,
                  "Frames over which a sudden change (a record's light changing by more than a quarter across its "
                  "window: a light that switches, a door that opens) may be interpolated; 0: such records are computed "
                  "at each frame their marks ask (default " + std::to_string(defaults.max_lag) + ")")
      ->check(CLI::Range(0LL, 239LL));
  cmd->add_option("--light-every", o.light_every,
                  "Records kept through a moving scene: for the parts' moves, the photon map, caustic map and light "
                  "guide are shot again only at the frames this divides, where the moves since their last shot passed "
                  "the photon radius (1: at any frame; a light that moves shoots them for each window's end; default " +
                      std::to_string(defaults.light_every) + ")")
      ->check(CLI::Range(1LL, 240LL));
  cmd->add_option("--stats", o.stats_path,
                  "Also write a CSV row a frame: time per pass, records, rays, device and host memory");
  cmd->add_option("--mp4", o.mp4_path,
                  "Also write an MP4 preview of the PNG frames with ffmpeg (H.264; needs ffmpeg installed)");
  return {cmd, [s, cmd] {
            WalkthroughRequest& walk = s->options.walk;
            s->camera.apply(walk.render.settings);
            s->environment.apply(walk.render.environment);
            s->method.apply(cmd, walk.render, s->options.quality);
            walk.cache = cache_mode_from_flags(s->per_frame, s->fixed, cmd->count("--cache-every") > 0,
                                               cmd->count("--cache-merge") > 0);
            return run_animate(s->options);
          }};
}

}  // namespace rcsplat
