// A render job: what a frame or a frame sequence is rendered from (a scene file or the built-in Cornell box, with
// the environment and limits asked for), what it is written to, and the cache files it reads and writes. `render`
// (cli/render_command.cpp) and walkthroughs (sequence/walkthrough.h) share it.
#pragma once
#include <string>
#include <vector>

#include "cl/gpu_context.h"
#include "image/image_io.h"
#include "render/frame_plan.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/scene_limits.h"

namespace rcsplat {

struct KeptCache;

struct RenderJob {
  std::string scene_path;  // empty: the built-in Cornell box
  // Images (.exr with layers, .png tone-mapped); a walkthrough's are frame patterns (util/frame_pattern.h).
  std::vector<std::string> outputs;
  std::string device;  // an index or a part of a name ("": the default device)
  RenderSettings settings;
  EnvironmentSettings environment;  // --sky, --environment (part of the scene once loaded)
  SceneLimits limits;               // --asset-root, --max-triangles, --max-host-memory, --max-device-memory
  float exposure = 0.0f;            // PNG outputs, in stops
  // Cache files (sequence/cache_file.h): the splat's kept records read before the first frame, written after the last.
  std::string cache_in, cache_out;
};

// The scene at path (glTF), or the built-in Cornell box for an empty path; a camera and light added where missing,
// placed for the camera the user chose (render/camera.h add_view_defaults).
// With the environment the options ask for (--sky, --environment), which also stands in for the default light.
// A glTF scene reads only what `limits` allows (scene/scene_limits.h, docs/SECURITY.md), placed in `pose` (its rest
// pose by default; scene/gltf_loader.h).
Scene load_scene(const std::string& path, int camera = 0, const CameraOverrides& overrides = {},
                 const EnvironmentSettings& environment = {}, const SceneLimits& limits = {},
                 const ScenePose& pose = {});
// The job's scene, in `pose` (its rest pose by default).
Scene load_scene(const RenderJob& job, const ScenePose& pose = {});

// --cache-in / --cache-out (sequence/cache_file.h): checked before any work (the splat only; --cache-out writable);
// then read into the renderer's kept records (or another KeptCache) for the plan's settings, or written from them.
// `animation`: the glTF animation that moves the reader's scene (-1: it stands still); a file whose records hold
// another (render/kept_records.h RecordTimes) is refused, naming both.
void check_cache_files(const RenderJob& job);
void load_cache_file(const GpuContext& gpu, Renderer& renderer, const Scene& scene, const FramePlan& plan,
                     const std::string& path, int animation = -1);
void load_cache_file(const GpuContext& gpu, KeptCache& kept, const Scene& scene, const FramePlan& plan,
                     const std::string& path, int animation = -1);
void save_cache_file(const GpuContext& gpu, Renderer& renderer, const Scene& scene, const FramePlan& plan,
                     const std::string& path);
void save_cache_file(const GpuContext& gpu, const KeptCache& kept, const Scene& scene, const FramePlan& plan,
                     const std::string& path);

// The EXR attributes of a render: scene, method, samples, bounces, environment, pixel samples.
ExrAttributes render_attributes(const Scene& scene, const RenderedImage& image, const RenderSettings& settings);
// How the lights pass glass, as an EXR records it (rcsplat:light_through_glass): "straight" or "caustics (N photon
// paths)"; --resume refuses another.
std::string light_through_glass_name(const GlassLight& glass);

}  // namespace rcsplat
