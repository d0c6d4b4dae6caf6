// A frame's settings, settled once: what the user asked for (RenderSettings, where 0 and `automatic` mean "let rcsplat
// choose") turned into what every pass reads, each automatic value chosen and each derived value computed here and
// nowhere else. The command line only parses; Renderer::plan (render/renderer.h) makes the plan, the passes read
// it and never check or change it again.
#pragma once
#include "render/bounce_choice.h"
#include "render/camera.h"
#include "render/frame_passes.h"
#include "render/settings.h"

namespace rcsplat {

// The plan's parts as the passes and the summary read them, each assembled from the one place its values are stored.
struct FrameImage {
  int width = 0, height = 0;       // output pixels
  unsigned side = 1, rounds = 1;   // sub-pixels a side of an output pixel; path tracing's rounds over the pixel's area
  int frame_width = 0, frame_height = 0;  // the G-buffer's frame: width x side, height x side
};
struct FrameBounces {
  unsigned count = 1;
  BounceMethod method = BounceMethod::path;
  bool chosen = false;          // chosen from the scene (--bounces 0)
  double kept_per_bounce = 0.0;  // the scene's measure it was chosen from
};
struct FrameRadiance {
  unsigned order = 0;  // HSH order of the radiance-cached lobes (0: the scene has none)
  float accuracy = 0.0f, captured_energy = 0.0f;
};

struct FramePlan {
  // The request with every automatic value settled, in output pixels: resolution, pixel_samples, bounces and
  // bounce_method, and, for a scene with radiance-cached lobes, hsh_order. What the summary and the files' attributes
  // report, and the one place each of these values is stored.
  RenderSettings settings;
  SceneCamera camera;
  // The image: settings.width x settings.height output pixels, each side x side sub-pixels of the G-buffer's frame
  // (render/pixel_samples.h), or 1 (one sample a pixel; also path tracing over the pixel's area, which instead renders
  // `rounds` frames of the image's size).
  unsigned side = 1, rounds = 1;
  int frame_width() const { return settings.width * int(side); }
  int frame_height() const { return settings.height * int(side); }
  // What the passes read, derived from `settings` and never stored: the samples divided among the sub-pixels and the
  // cache's pixel distances (reach, Hessian budget, placement spacing) in sub-pixels (sub_pixel_settings), or
  // `settings` itself at one sample a pixel.
  RenderSettings frame_settings() const;
  FrameImage image() const {
    return {settings.width, settings.height, side, rounds, frame_width(), frame_height()};
  }
  FrameBounces bounces() const {
    return {settings.bounces, settings.bounce_method, bounces_chosen, kept_per_bounce};
  }
  CacheSettings cache() const { return frame_settings().cache; }  // in sub-pixels
  FrameRadiance radiance() const {
    return {passes.radiance_records ? settings.hsh_order : 0u, radiance_accuracy, hsh_captured_energy};
  }
  unsigned light_strata = 0;  // per axis, each sub-pixel's (or round's) direct light
  // Whether the bounce count was chosen from the scene, and the scene's measure it was chosen from; the count and the
  // method themselves are settings.bounces and settings.bounce_method (render/bounce_choice.h).
  bool bounces_chosen = false;
  double kept_per_bounce = 0.0;
  // The passes and maps the frame runs (render/frame_passes.h), decided once here.
  FramePasses passes;
  // Radiance-cached lobes (0 without): accuracy a times the sharpest cached roughness, at least a / 2, and the share
  // of the sharpest lobe the order holds.
  float radiance_accuracy = 0.0f, hsh_captured_energy = 0.0f;
};

// The largest counts a request may ask for (check_request holds it to them; the help texts print them).
constexpr unsigned kMaxLightSamples = 1u << 20, kMaxPathSamples = 1u << 20, kMaxGlossySamples = 1u << 16;
constexpr unsigned kMaxPhotonPaths = 1u << 26;  // --photons and --caustic-photons

// Every range of a request, checked once, each message naming its option (--accuracy, --bounces, --hsh-order,
// --pixel-samples, --hemisphere, --spacing, ...). Throws rcsplat::Error. The command line calls it before it loads
// the scene; Renderer::plan calls it again for library callers.
void check_request(const RenderSettings& request);

}  // namespace rcsplat
