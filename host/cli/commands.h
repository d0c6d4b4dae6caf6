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
#include "render/settings_text.h"
#include "sequence/render_job.h"
#include "sequence/walkthrough.h"

namespace rcsplat {

struct DevicesOptions {
  std::string json_path;
};
int run_devices(const DevicesOptions& options);

// render and reference: the job (sequence/render_job.h) and what the command does besides.
struct RenderOptions : RenderJob {
  std::string json_path;        // the summary as JSON
  bool progress_lines = false;  // --progress-lines: "Progress: NN%" lines on stdout (util/log.h)
  bool resume = false;   // reference: add samples to the .exr output written by an earlier run
  bool denoise = false;  // render --denoise: Open Image Denoise on the per-pixel sampled layers (render/denoise_frame.h)
  std::string quality = kDefaultQuality;  // render --quality: draft, standard, final (apply_quality)
};
int run_render(const RenderOptions& options);
// `reference`'s default path samples per pixel (and light samples, unless --light-samples is given).
constexpr unsigned kReferenceSamples = 1024;

// A reference continued: reads the path-traced layers of the earlier .exr at `path`, renders the missing samples with
// other seeds and merges both, weighted by their sample counts. Throws rcsplat::Error when the file does not belong to
// this scene and frame. Returns false when the file already has the samples asked for.
bool resume_reference(GpuContext& gpu, const Scene& scene, const RenderOptions& options, const std::string& path,
                      RenderedImage& image);

// `rcsplat animate`: the walkthrough library's request (sequence/walkthrough.h) with the command's summary.
struct AnimateOptions {
  WalkthroughRequest walk;
  std::string json_path;
  bool progress_lines = false;
  std::string quality = kDefaultQuality;
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
// The scene plan's lines (info and the render summary) and its JSON.
void print_scene_plan(const ScenePlan& plan, int bvh_depth);
nlohmann::json scene_plan_json(const ScenePlan& plan, int bvh_depth);

struct CompareOptions {
  std::string image_path, reference_path, heatmap_path, flip_heatmap_path, json_path;
  std::string heatmap_layer = "full";  // or "indirect"
  int block = 8;                       // block relMSE over block x block pixel means
  float exposure = 0.0f;               // the tone mapping FLIP judges, in stops as for PNGs
};
int run_compare(const CompareOptions& options);

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
  bool progress_lines = false;  // --progress-lines (util/log.h)
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

}  // namespace rcsplat
