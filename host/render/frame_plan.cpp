#include "render/frame_plan.h"

#include <cmath>
#include <string>

#include "kernels/hsh.h"
#include "render/pixel_samples.h"
#include "util/error.h"

namespace rcsplat {

RenderSettings FramePlan::frame_settings() const {
  return side > 1 ? sub_pixel_settings(settings, settings.width, settings.height, side) : settings;
}

void check_request(const RenderSettings& r) {
  auto range = [](const char* option, long long value, long long lo, long long hi, const char* zero) {
    if (value < lo || value > hi)
      throw Error(std::string(option) + " must be between " + std::to_string(lo == 0 ? 1 : lo) + " and " +
                  std::to_string(hi) + zero + " (given " + std::to_string(value) + ")");
  };
  range("--width", r.width, 0, 16384, " (0: from the camera)");
  range("--height", r.height, 0, 16384, " (0: from the camera)");
  range("--bounces", r.bounces, 0, kMaxBounces, " (0: chosen from the scene)");
  range("--hsh-order", r.hsh_order, 0, HSH_MAX_ORDER, " (0: chosen from the roughness)");
  range("--light-samples", r.light_samples, 0, kMaxLightSamples, "");
  range("--glossy-samples", r.glossy_samples, 1, kMaxGlossySamples, "");
  range("--spp", r.path.samples, 1, kMaxPathSamples, "");
  range("--photons", r.photon_paths, 0, kMaxPhotonPaths, " (0: rounds until the map is full)");
  range("--caustic-photons", r.caustic_photons, 0, kMaxPhotonPaths, " (0: no caustic map)");
  range("RenderSettings::photon_neighbours", r.photon_neighbours, 1, 1 << 16, "");
  if (!(r.short_ray_paths >= 0.0f) || !std::isfinite(r.short_ray_paths))
    throw Error("--short-ray-paths must be 0 or positive (given " + std::to_string(r.short_ray_paths) + ")");
  if (!(r.photon_min_support >= 0.0f) || !std::isfinite(r.photon_min_support))
    throw Error("--photon-min-support must be 0 or positive (given " + std::to_string(r.photon_min_support) + ")");
  if (r.pixel_samples) pixel_sample_side(r.pixel_samples);  // a square number from 1 to 64
  validate_cache_settings(r.cache);
}

}  // namespace rcsplat
