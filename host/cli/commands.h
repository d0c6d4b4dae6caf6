// The rcsplat subcommands. Each returns the process exit code; rcsplat::Error escapes to main, which prints it.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <functional>
#include <string>
#include <vector>

#include "cl/gpu_context.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/scene_limits.h"
#include "scene/scene_plan.h"

namespace rcsplat {

struct DevicesOptions {
  std::string json_path;
};
int run_devices(const DevicesOptions& options);

struct RenderOptions {
  std::string scene_path;  // empty: the built-in Cornell box
  std::vector<std::string> outputs;
  std::string device;
  RenderSettings settings;
  EnvironmentSettings environment;  // --sky, --environment (part of the scene once loaded)
  SceneLimits limits;               // --asset-root, --max-triangles, --max-host-memory, --max-device-memory
  float exposure = 0.0f;
  std::string json_path;
  bool progress_lines = false;  // --progress-lines: "Progress: NN%" lines on stdout (util/log.h)
  bool resume = false;  // reference: add samples to the .exr output written by an earlier run
  bool denoise = false;  // render --denoise: Open Image Denoise on the per-pixel sampled layers (render/denoise_frame.h)
  std::string quality = "standard";  // render --quality: draft, standard, final (apply_quality)
  // Cache files (render/cache_file.h): the splat's kept records read before the first frame, written after the last.
  std::string cache_in, cache_out;
};
// --quality: draft, standard (the defaults) or final sets accuracy, rays per record, pixel and light samples, except
// those whose option was given (`given("--accuracy")`). quality_summary says what the request holds after it, for the
// summary, and whether given options replaced some of the preset's.
void apply_quality(const std::string& quality, RenderSettings& settings,
                   const std::function<bool(const char*)>& given);
std::string quality_summary(const std::string& quality, const RenderSettings& settings);
int run_render(const RenderOptions& options);
// `reference`'s default path samples per pixel (and light samples, unless --light-samples is given).
constexpr unsigned kReferenceSamples = 1024;

// A reference continued: reads the path-traced layers of the earlier .exr at `path`, renders the missing samples with
// other seeds and merges both, weighted by their sample counts. Throws rcsplat::Error when the file does not belong to
// this scene and frame. Returns false when the file already has the samples asked for.
bool resume_reference(GpuContext& gpu, const Scene& scene, const RenderOptions& options, const std::string& path,
                      RenderedImage& image);

// `rcsplat animate`: a camera path (render/camera_path.h) rendered to a numbered frame sequence.
struct AnimateOptions {
  RenderOptions render;  // outputs are frame patterns (util/frame_pattern.h); --eye and the like start an --orbit
  std::string keyframes;     // a keyframe file; else
  double orbit_seconds = 0;  // an orbit of this many seconds, sweeping orbit_degrees; else the scene's glTF animation:
  double orbit_degrees = 360.0;
  int animation = 0;
  double fps = 24.0;
  long long first_frame = 0, last_frame = -1;  // -1: the path's last frame
  std::string stats_path;  // a CSV row a frame
  std::string mp4_path;    // a preview made by ffmpeg from the PNG frames
  bool cache_per_frame = false;            // else irradiance records are kept across frames (render/kept_records.h)
  // With --cache-in: every frame starts from the file's records alone, so a frame is the same bits whatever range of
  // frames a process renders (a walkthrough split over processes or machines).
  bool cache_fixed = false;
  // Render only the frames whose outputs are not all there (a rerun or a requeue of a stopped task); the frames must
  // not depend on each other (cache_fixed or cache_per_frame).
  bool skip_existing = false;
  // The cache pre-pass (render/cache_merge.h, docs/FARM.md): with cache_every K > 0, only the range's frames that K
  // divides are rendered, each from no records (the light kept), and --cache-out gets their records tagged by frame;
  // -o is optional. With cache_merge, no frame is rendered: those part files are merged into --cache-out.
  long long cache_every = 0;
  std::vector<std::string> cache_merge;
  // --kept-records is render.settings.kept_records_capacity.
};
int run_animate(const AnimateOptions& options);

// `rcsplat flicker`: a sequence's temporal relMSE (image/flicker.h), less a reference sequence's.
struct FlickerOptions {
  std::string frames, reference;  // frame patterns (util/frame_pattern.h)
  std::string positions;          // the frames' position, depth and camera from this sequence ("": the frames')
  long long first_frame = 0, last_frame = -1;  // -1: up to the first frame missing
  std::string layer = "indirect";              // or "full"
  bool demodulate = false;                     // the layer over the albedo layer
  std::string json_path;
};
int run_flicker(const FlickerOptions& options);

struct InfoOptions {
  std::string scene_path;  // empty: the built-in Cornell box
  std::string json_path;
  std::string device;  // for the bounce probe; none available: info says so and goes on
  EnvironmentSettings environment;
  SceneLimits limits;
};
int run_info(const InfoOptions& options);
// The scene plan's lines (info and the render summary), its JSON, and the kernel switches with the BVH's stack size.
void print_scene_plan(const ScenePlan& plan, int bvh_depth);
nlohmann::json scene_plan_json(const ScenePlan& plan, int bvh_depth);
std::map<std::string, std::string> plan_switches(const ScenePlan& plan, int bvh_depth);

struct CompareOptions {
  std::string image_path, reference_path, heatmap_path, flip_heatmap_path, json_path;
  std::string heatmap_layer = "full";  // or "indirect"
  int block = 8;                       // block relMSE over block x block pixel means
  float exposure = 0.0f;               // the tone mapping FLIP judges, in stops as for PNGs
};
int run_compare(const CompareOptions& options);

// Parsers for the render options; each throws rcsplat::Error naming the option on bad input.
GiMethod parse_gi_method(const std::string& name);
BounceMethod parse_bounce_method(const std::string& name);
void parse_hemisphere(const std::string& text, CacheSettings& cache, bool fine = false);  // "MxN"
void parse_spacing(const std::string& text, CacheSettings& cache);     // "MIN,MAX"

// `rcsplat sweep`: every combination of cache settings, and path tracing at several sample counts (plain and, where
// the benchmark Python environment has pyoidn, denoised), rendered on one device and judged against a reference.
struct SweepOptions {
  std::string scene_path, reference_path, output_dir, device;
  std::vector<float> accuracies = {0.15f, 0.3f, 0.6f};
  std::vector<std::string> hemispheres = {"16x32"};
  std::vector<unsigned> hsh_orders;  // empty: chosen from the scene
  std::vector<unsigned> path_samples = {4, 16, 64};
  std::string denoise = "auto";  // auto | on | off
  bool plot = true;
  unsigned light_samples = 16, pixel_samples = 0, bounces = 0;  // bounces 0: the reference's
  int camera = 0;
  EnvironmentSettings environment;
  SceneLimits limits;
  int block = 8;
  float exposure = 0.0f;
};
int run_sweep(const SweepOptions& options);

// Timed runs `bench` takes the median of: frames per device, or the traversal's paired runs.
constexpr int kBenchFrameRepeats = 3, kBenchTraversalRepeats = 5;
struct BenchOptions {
  std::string scene_path;  // empty: frames of the built-in Cornell box; --traversal: Sponza from ../shared/scenes
                           // when present, else a generated mesh
  std::string device;
  // Frames (the default): the same render on each device: "" the default device, "all" every usable one, or a
  // comma-separated list of indices or name parts.
  std::string devices;
  int width = 1024, height = 768;
  bool traversal = false;  // the traversal kernel against Embree instead
  size_t rays = 1u << 20;
  size_t record_points = 4096;
  int repeats = kBenchTraversalRepeats;  // frames: kBenchFrameRepeats unless --repeats is given
  std::string json_path;
  SceneLimits limits;
};
int run_bench(const BenchOptions& options);
int run_bench_frames(const BenchOptions& options);
// Sponza from ../shared/scenes beside the source tree, or "" when it is not there.
std::string default_bench_scene();

// The scene at path (glTF), or the built-in Cornell box for an empty path; a camera and light added where missing,
// placed for the camera the user chose (render/camera.h add_view_defaults).
// With the environment the options ask for (--sky, --environment), which also stands in for the default light.
// A glTF scene reads only what `limits` allows (scene/scene_limits.h, docs/SECURITY.md), placed in `pose` (its rest
// pose by default; scene/gltf_loader.h).
Scene load_scene(const std::string& path, int camera = 0, const CameraOverrides& overrides = {},
                 const EnvironmentSettings& environment = {}, const SceneLimits& limits = {},
                 const ScenePose& pose = {});

// --cache-in / --cache-out (render/cache_file.h): checked before any work (the splat only; --cache-out writable);
// then read into the renderer's kept records (or another KeptCache) for the plan's settings, or written from them.
void check_cache_files(const RenderOptions& options);
void load_cache_file(const GpuContext& gpu, Renderer& renderer, const Scene& scene, const FramePlan& plan,
                     const std::string& path);
void load_cache_file(const GpuContext& gpu, KeptCache& kept, const Scene& scene, const FramePlan& plan,
                     const std::string& path);
void save_cache_file(const GpuContext& gpu, Renderer& renderer, const Scene& scene, const FramePlan& plan,
                     const std::string& path);
void save_cache_file(const GpuContext& gpu, const KeptCache& kept, const Scene& scene, const FramePlan& plan,
                     const std::string& path);

// The EXR attributes of a render: scene, method, samples, bounces, environment, pixel samples.
ExrAttributes render_attributes(const Scene& scene, const RenderedImage& image, const RenderSettings& settings);

// Writes text to path atomically (temporary file, then rename). Throws rcsplat::Error.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace rcsplat
