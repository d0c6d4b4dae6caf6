// What --bounces and --bounce-method become when left to the scene (0 and auto): the bounce count from how much light
// each reflection keeps in this scene, measured by a few photons from its lights and its environment, the sky's
// smooth part included (the reflected flux of each landing over the last's: albedo and openness together), and the
// method from what the scene allows.
#pragma once
#include <functional>

#include "cl/device_scene.h"
#include "render/settings.h"

namespace rcsplat {

// Bounces are added until the light of those left out is at most this share of the indirect light.
constexpr double kMissingIndirectShare = 0.05;
// The most bounces the scene may choose: photons make a bounce nearly free for the records; path continuation (what a
// scene with an environment gets) costs a record's rays again for each. Chosen from the scene, not the method, so that
// a render and its path-traced reference agree.
constexpr unsigned kMaxChosenBouncesPhotons = 8, kMaxChosenBouncesPath = 3;

struct BounceChoice {
  unsigned bounces = 1;
  BounceMethod method = BounceMethod::path;
  // The scene's measure: reflected flux of landings 1 .. 3 over that of landings 0 .. 2 (0 without photons: a scene lit
  // by nothing), and whether the bounce count was chosen from it.
  double kept_per_bounce = 0.0;
  bool bounces_chosen = false;
};

// The method for `settings` (auto: photons for the cache methods where the scene allows, else path) and the bounce
// count (settings.bounces, or for 0 the fewest that leave out at most kMissingIndirectShare of the indirect light
// when each bounce keeps kept_per_bounce of the last's, at most 8, or 3 in a scene with an environment).
// measure_kept_per_bounce: the scene's measure (kept_per_bounce below), asked for only when the count is chosen.
BounceChoice choose_bounces(const Scene& scene, const RenderSettings& settings,
                            const std::function<double()>& measure_kept_per_bounce);

// The scene's measure: reflected flux of landings 1 .. 3 over that of landings 0 .. 2, by a few photons from its
// lights and its environment (kBounceProbe* in bounce_choice.cpp).
double kept_per_bounce(GpuContext& gpu, const DeviceScene& device_scene);

// The same, measuring on the device when the count is chosen (`info` and tests; the Renderer keeps its measure).
inline BounceChoice choose_bounces(GpuContext& gpu, const Scene& scene, const DeviceScene& device_scene,
                                   const RenderSettings& settings) {
  return choose_bounces(scene, settings, [&] { return kept_per_bounce(gpu, device_scene); });
}

// The fewest bounces N >= 1 with kept^N <= kMissingIndirectShare, at most max_bounces.
unsigned bounces_for(double kept_per_bounce, unsigned max_bounces);

}  // namespace rcsplat
