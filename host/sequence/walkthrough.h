// A walkthrough: a camera path (sequence/camera_path.h) rendered frame by frame by one Renderer (the BVH, programs,
// photon map and light guide are made once), each frame written as soon as it is done, with a row of statistics a
// frame and, where ffmpeg is installed, an MP4 preview. Its records live on across frames as the cache mode says, and
// a walkthrough split over tasks is a pre-pass of key frames, a merge of their cache files and tasks that render from
// the merged file (docs/FARM.md). `rcsplat animate` parses its options into a WalkthroughRequest and calls
// render_walkthrough.
#pragma once
#include <string>
#include <vector>

#include "render/frame.h"
#include "sequence/cache_merge.h"
#include "sequence/frame_table.h"
#include "sequence/render_job.h"

namespace rcsplat {

// What becomes of a walkthrough's records from frame to frame: one type for what the command line spreads over
// --cache-per-frame, --cache-fixed, --cache-every and --cache-merge.
enum class CacheMode {
  kept,       // the default: the splat keeps its records across frames and places new ones only where none reaches
  per_frame,  // --cache-per-frame: every frame places its records anew, as `render` does
  fixed,      // --cache-fixed: every frame starts from the --cache-in file's records alone (a frame's are dropped)
  pre_pass,   // --cache-every K: only the key frames K divides, each from no records; their records to --cache-out
  merge,      // --cache-merge PART...: no frame; the pre-pass parts merged into --cache-out
};
const char* cache_mode_name(CacheMode mode);  // "kept_records", "per_frame", "fixed", "pre_pass", "merge"
// The mode the command line's flags ask for; throws rcsplat::Error naming the flags when they ask for two.
CacheMode cache_mode_from_flags(bool per_frame, bool fixed, bool pre_pass, bool merge);

struct WalkthroughRequest {
  RenderJob render;  // outputs are frame patterns (util/frame_pattern.h); --eye and the like start an --orbit
  // The camera path: a keyframe file; else an orbit of orbit_seconds sweeping orbit_degrees; else the scene's glTF
  // animation `animation`.
  std::string keyframes;
  double orbit_seconds = 0.0;
  double orbit_degrees = 360.0;
  int animation = 0;
  double fps = 24.0;
  long long first_frame = 0, last_frame = -1;  // -1: the path's last frame
  CacheMode cache = CacheMode::kept;
  long long cache_every = 0;              // pre_pass: a key frame every K frames
  std::vector<std::string> cache_merge;  // merge: the pre-pass parts
  // Render only the frames whose outputs are not all there (a rerun or a requeue of a stopped task); the frames must
  // not depend on each other (CacheMode::fixed or per_frame).
  bool skip_existing = false;
  // Records kept through a moving scene (issue 62): a move marks the kept records whose light it may have changed by
  // more than this fraction (render/kept_records.h moved_record_change), to be computed again where they stand.
  double moved_record_tolerance = 0.01;
  // Temporal windows (issue 62 item 3; docs/ALGORITHM.md section 15): a record a move marked is computed again at its
  // frame and, with the scene posed temporal_window frames later, at that frame too; the frames between interpolate
  // its light. 1: no windows. A record whose light changes across the window by more than a quarter (a light that
  // switches, a door that opens) is interpolated over max_lag + 1 frames at most; 0: computed again at each frame
  // its marks ask for, as without windows.
  long long temporal_window = 8;
  long long max_lag = 0;
  // Records kept through a moving scene: for the parts' moves, the light that depends on where things are (photon
  // map, caustic map, light guide) is shot again only at the frames this divides, where the parts moved past the
  // photon radius since its last shot; the frames between hold it. 1: at any frame the moves call for it. A light
  // that moves shoots it for each temporal window's end (or, without windows, at once). A farm's frames take their
  // key frame's (docs/FARM.md).
  long long light_every = 8;
  std::string stats_path;  // a CSV row a frame, rewritten after each frame
  std::string mp4_path;    // a preview made by ffmpeg from the PNG frames
};

// Every range and combination of a request, checked in one place before any work; throws rcsplat::Error naming the
// option.
void check_walkthrough(const WalkthroughRequest& request);

struct WalkthroughResult {
  std::string scene, device;  // the scene's source and the device's name
  std::string path_description;
  double path_duration = 0.0;
  long long first = 0, last = 0;  // the frames asked for
  std::vector<FrameRow> rows;     // the frames rendered (a pre-pass: its key frames)
  long long skipped = 0;          // frames whose files were there already (skip_existing)
  int width = 0, height = 0;
  double wall_s = 0.0;
  bool mp4_written = false;
  uint64_t pre_pass_irradiance = 0, pre_pass_radiance = 0;  // records tagged by key frame (pre_pass)
  CacheMergeStats merge;                                     // a merge's key frames and records read and kept
};

// Checks, renders and writes the walkthrough (or, CacheMode::merge, merges its parts). Throws rcsplat::Error.
WalkthroughResult render_walkthrough(const WalkthroughRequest& request);

}  // namespace rcsplat
