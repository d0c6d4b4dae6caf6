#include "kernels/counter_random.h"
#include "render/bounce_choice.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "passes/light_guide_pass.h"
#include "util/colour.h"

namespace rcsplat {
namespace {

constexpr unsigned kProbePhotons = 1u << 16, kProbeLandings = 4;
// A seed of its own, the same for every render of the scene: render and reference choose the same count.
constexpr unsigned kProbeSeed = STREAM_BOUNCE_PROBE;

// Reflected flux of landings 1 .. 3 over landings 0 .. 2 (luminance) of photons from the lights and the
// environment's peak, and, with sky_power > 0, its smooth part; 0 when no photon lands.
double kept_per_bounce(GpuContext& gpu, const DeviceScene& device_scene, double sky_power) {
  std::vector<PhotonHit> hits =
      LightGuidePass(gpu, device_scene, sky_power).shoot(kProbePhotons, kProbeSeed, kProbeLandings);
  double flux[kProbeLandings] = {};
  for (size_t i = 0; i < hits.size(); ++i)
    flux[i % kProbeLandings] += luminance(hits[i].flux);
  double before = flux[0] + flux[1] + flux[2], after = flux[1] + flux[2] + flux[3];
  return before > 0.0 && std::isfinite(before) && std::isfinite(after) ? after / before : 0.0;
}

}  // namespace

// The larger of the lights' measure and the measure with the sky's smooth part added: a sky mostly lights a scene's
// outside, whose reflections leave (Sponza under a white sky: 8% against its sun's 41%), and must not take away the
// bounces the lights' light needs inside; a scene lit by a sky alone gets the sky's.
double kept_per_bounce(GpuContext& gpu, const DeviceScene& device_scene) {
  // The sky's power as the probe's photons carry it: pi (the unit disc they cross) times its luminance over the sphere.
  const double lights = kept_per_bounce(gpu, device_scene, 0.0),
               sky = std::numbers::pi * device_scene.environment_smooth_power();
  return sky > 0.0 ? std::max(lights, kept_per_bounce(gpu, device_scene, sky)) : lights;
}

unsigned bounces_for(double kept, unsigned max_bounces) {
  unsigned n = 1;
  double left_out = kept;  // the share of the indirect light beyond n bounces, for a geometric series
  while (n < max_bounces && left_out > kMissingIndirectShare) {
    ++n;
    left_out *= kept;
  }
  return n;
}

BounceChoice choose_bounces(const Scene& scene, const RenderSettings& settings,
                            const std::function<double()>& measure_kept_per_bounce) {
  BounceChoice choice;
  const bool cache = settings.gi == GiMethod::splat || settings.gi == GiMethod::octree;
  choice.method = settings.bounce_method;
  if (choice.method == BounceMethod::automatic)
    choice.method = cache && !scene.environment.present() ? BounceMethod::photons : BounceMethod::path;
  choice.bounces = settings.bounces;
  if (settings.bounces == 0) {
    choice.kept_per_bounce = measure_kept_per_bounce();
    // From the scene alone, so that a render and its reference (path traced) choose the same count.
    choice.bounces = bounces_for(choice.kept_per_bounce, scene.environment.present() ? kMaxChosenBouncesPath
                                                                                     : kMaxChosenBouncesPhotons);
    choice.bounces_chosen = true;
  }
  return choice;
}

}  // namespace rcsplat
