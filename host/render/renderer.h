// The renderer: made once per scene and device, it renders any number of frames. It owns what does not change from
// frame to frame: the scene in the device's coordinates (scene/scene_frame.h), the BVH, the device scene, the
// programs (through the GpuContext's cache), every pass with its buffers (the primary passes, and the last frame's
// method's: render/indirect.h MethodPasses), the bounce probe's measure, the lobe table of radiance-cached materials,
// the photon map and the light guide (the last two rebuilt only when the settings they depend on change). A frame is
// planned (render/frame_plan.h), then rendered: primary visibility, direct light, then indirect light by radiance cache
// splatting (or the classic octree lookup, or path tracing), and composition.
#pragma once
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "bvh/moving_bvh.h"
#include "cl/gpu_context.h"
#include "render/frame.h"
#include "render/frame_plan.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "scene/scene_frame.h"
#include "util/log.h"

namespace rcsplat {

class DeviceScene;
class GBufferPass;
class DirectPass;
class GlassMirrorPass;
class GlassCausticsPass;
class LayerPass;
struct RadianceLobeTable;
struct ViewIndependentLight;
struct MethodPasses;
struct KeptCache;

class Renderer {
 public:
  // Builds the BVH and uploads the scene. forced_switches: kernel switches compiled on whether the scene needs them
  // or not (tests; scene/scene_plan.h). gpu and scene must outlive the renderer.
  // moving_parts: triangle ranges of the scene that will move rigidly (scene/scene_animator.h): each gets a BVH of
  // its own under a top level (bvh/moving_bvh.h), so that move() refits it alone. None: one BVH, as a still scene.
  Renderer(GpuContext& gpu, const Scene& scene, const std::set<std::string>& forced_switches = {},
           const std::vector<TriangleRange>& moving_parts = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The request settled for this scene and device (render/frame_plan.h): may run the bounce probe and the lobe table
  // the first time a request needs them. Throws rcsplat::Error, naming the option, for a request out of range.
  FramePlan plan(const RenderSettings& request);
  // One frame. Its statistics carry the setup (BVH, upload, probe, kernel builds) only where this frame paid for it:
  // the first frame of a renderer does, later frames do not.
  RenderedImage render(const FramePlan& plan);
  RenderedImage render(const RenderSettings& request) { return render(plan(request)); }

  // The scene (the one given at construction, changed in place) moved: the listed parts (indices into moving_parts)
  // and, where lights_moved, its lights. Refits the moved parts' BVH and writes what they changed to the device. The
  // light that depends on where things are (photon map, caustic map, light guide, glass caustic map) is made again
  // once the moves since it was made add up to the photon map's gather radius, or at once where a light moved. Kept
  // records (RenderSettings::keep_records) whose light the moves may have changed by more than record_tolerance of
  // itself are marked as moved (KeptRecords::mark_moved; a light that moves marks them all): the next frame that sees
  // one computes an irradiance record again where it is, and places a radiance record again. The next frame's
  // statistics count the work (bvh_build_s, upload_s). Returns the records marked.
  struct PartMove {
    size_t part;          // index into moving_parts
    double displacement;  // how far any of its points moved, world units
  };
  size_t move(const std::vector<PartMove>& moved_parts, bool lights_moved, double record_tolerance);

  // Drops the light that depends on where things are (photon map, caustic map, light guide; the glass caustic map is
  // shot again now), so that the next frame shoots it with the scene as it is posed then: a frame whose light must
  // not depend on the frames before it (a cache pre-pass's key frame, a fixed cache's frame, of a moving scene).
  void forget_light();
  // Held, the light changes only by forget_light: a move never makes it again, however far the parts go (a fixed
  // cache's frames of a moving scene share the light of their key frame, sequence/walkthrough.cpp).
  // `through_light_moves` false: held against the parts' moves alone, and a light that moves makes it again at once
  // (records kept through a moving scene shoot it again for their parts only at the frames --light-every divides:
  // photons carry a lamp's light from its second bounce on, and a carried lamp's lags visibly), unless windows follow
  // the light and shoot it for their ends (look_ahead_with_its_light). Let go, the next move, or the next call with
  // no move, makes it again if the moves while it was held call for it.
  void hold_light(bool held, bool through_light_moves = true) {
    light_held_ = held;
    light_held_through_light_moves_ = held && through_light_moves;
  }
  // Whether the light that depends on where things are holds photons (a photon map or a caustic map): then records
  // computed with the scene posed ahead would gather photons shot for the frame's pose.
  bool has_photons() const;
  bool has_caustic_map() const;

  // Temporal windows (issue 62 item 3; docs/ALGORITHM.md section 15). The scene (changed in place) was posed at a
  // later time: refits and uploads what the parts' moves changed, and nothing else (no record is marked, the photons
  // stay). A look ahead poses the scene there, calls look_ahead, and poses it back the same way.
  void pose_for_look_ahead(const std::vector<PartMove>& moved_parts);
  // Computes the irradiance records the last frame computed again in place once more, with the scene as it is posed
  // now (at `end`, seconds): each whose light differs from the frame's by at most sudden_change of the larger gets a
  // window from the frame's time to `end` (KeptRecords::set_window), over which later frames interpolate its light.
  struct LookAhead {
    uint32_t computed = 0, windows = 0;
  };
  LookAhead look_ahead(double end, double sudden_change);
  // A light that moves (issue 62 item 4): the look ahead above, with the records' photons and light guide shot for
  // the scene as it is posed now (at `end`) rather than the frame's: made once for each `end` (`plan`, the last frame's,
  // says what to make) and kept until the frames reach it (take_light_ahead). Only without a caustic map.
  LookAhead look_ahead_with_its_light(double end, double sudden_change, const FramePlan& plan);
  // At the frame of time `now`, after its move: the light shot ahead for it, if any, becomes the light (photons shot
  // for this pose; forget_light leaves it be).
  void take_light_ahead(double now);
  // Whether a light that moves is followed by windows (look_ahead_with_its_light) rather than by letting the records
  // it marks go (Renderer::move).
  void follow_lights_by_windows(bool follow) { lights_by_windows_ = follow; }
  bool follows_lights_by_windows() const { return lights_by_windows_; }

  const DeviceScene& device_scene() const { return *device_scene_; }
  // The irradiance and radiance records kept across frames (RenderSettings::keep_records), made empty on first use:
  // cache files (sequence/cache_file.h) read into it before a frame and write it after one.
  KeptCache& kept_records();

 private:
  double kept_per_bounce();
  void forget_light_if_moved();  // drops the light where the moves since it was shot call for it (move)
  // Refits the moved parts' BVH and writes what they changed to the device; returns the rows it changed.
  MovingBvh::Changed move_geometry(const std::vector<PartMove>& moved_parts, double& bvh_s, double& upload_s);
  // Starts building every program the planned frame will use (GpuContext::build_ahead), so that they compile side by
  // side and beside the frame's first passes; a program a frame asks for that is not among them builds when asked.
  void build_programs_ahead(const FramePlan& plan);
  const RadianceLobeTable& lobe_table(unsigned seed);
  void surface_layers(RenderedImage& img, bool colour_on_host);
  void shade_frame(const FramePlan& plan, const CameraParams& camera, const RenderSettings& settings,
                   RenderedImage& img, Progress* progress = nullptr, size_t progress_done_before = 0);
  void path_trace_pixel_area(const FramePlan& plan, const CameraParams& camera, RenderedImage& img);
  void shoot_glass_caustic_map();

  GpuContext& gpu_;
  const Scene& scene_;
  std::set<std::string> forced_switches_;
  SceneFrame scene_frame_;
  SceneStats scene_stats_;  // what every frame reports of the scene; its times (setup_) only the first frame
  std::vector<TriangleRange> moving_parts_;
  std::unique_ptr<MovingBvh> moving_bvh_;  // with moving parts
  double moved_since_photons_ = 0.0;       // world units the parts have moved since the photons were shot (move())
  bool lights_moved_since_photons_ = false;
  bool light_held_ = false;                // hold_light
  bool light_held_through_light_moves_ = false;
  bool lights_by_windows_ = false;                      // follow_lights_by_windows
  struct LightAhead;
  std::unique_ptr<LightAhead> light_ahead_;  // look_ahead_with_its_light's, until the frames reach its time
  std::unique_ptr<DeviceScene> device_scene_;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<DirectPass> direct_;
  std::unique_ptr<GlassMirrorPass> glass_mirror_;  // scenes with glass
  std::unique_ptr<GlassCausticsPass> glass_caustics_;  // --light-through-glass caustics with a glass volume
  std::unique_ptr<LayerPass> layers_;
  std::unique_ptr<ViewIndependentLight> light_;
  std::unique_ptr<MethodPasses> passes_;  // the last frame's method's
  std::unique_ptr<KeptCache> kept_records_;  // RenderSettings::keep_records
  std::optional<double> kept_per_bounce_;
  unsigned lobe_table_seed_ = 0;
  std::unique_ptr<RadianceLobeTable> lobe_table_;
  // Setup done since the last frame (BVH, upload, probe, lobe table, kernel builds): the next frame reports it.
  RenderStats setup_;
  double setup_seconds_ = 0.0;
};

// One frame with a renderer made for it: what `render` and most tests use.
RenderedImage render(GpuContext& gpu, const Scene& scene, const RenderSettings& settings);

}  // namespace rcsplat
