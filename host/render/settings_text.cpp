#include "render/settings_text.h"

#include <cstdio>

#include "util/error.h"

namespace rcsplat {

GiMethod parse_gi_method(const std::string& name) {
  for (GiMethod m : {GiMethod::none, GiMethod::splat, GiMethod::octree, GiMethod::path})
    if (name == gi_method_name(m)) return m;
  throw Error("--gi " + name + ": unknown method (use splat, octree, path or none)");
}

BounceMethod parse_bounce_method(const std::string& name) {
  for (BounceMethod m : {BounceMethod::automatic, BounceMethod::path, BounceMethod::photons})
    if (name == bounce_method_name(m)) return m;
  throw Error("--bounce-method " + name + ": unknown method (use auto, path or photons)");
}

void parse_hemisphere(const std::string& text, CacheSettings& cache, bool fine) {
  unsigned m = 0, n = 0;
  char tail = 0;
  std::string option = fine ? "--fine-hemisphere " : "--hemisphere ";
  if (std::sscanf(text.c_str(), "%ux%u%c", &m, &n, &tail) != 2 || m == 0 || n == 0)
    throw Error(option + text + ": expected MxN, for example 16x32");
  // Parsed only: the frame plan checks the range (render/frame_plan.h check_request).
  (fine ? cache.fine_theta_strata : cache.theta_strata) = m;
  (fine ? cache.fine_phi_strata : cache.phi_strata) = n;
}

void parse_spacing(const std::string& text, CacheSettings& cache) {
  float lo = 0, hi = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%f,%f%c", &lo, &hi, &tail) != 2)
    throw Error("--spacing " + text + ": expected MIN,MAX in pixels, for example 3,20");
  cache.min_reach_pixels = lo;
  cache.max_reach_pixels = hi;
}

namespace {

// What each --quality sets (standard: the library's defaults, RenderSettings and CacheSettings).
struct QualityPreset {
  const char* name;
  float accuracy;
  unsigned theta_strata, phi_strata, light_samples;
  unsigned pixel_samples, preferred_pixel_samples;  // 0: chosen, up to preferred_pixel_samples
};

QualityPreset quality_preset(const std::string& quality) {
  const RenderSettings defaults;
  const QualityPreset standard{"standard",
                               defaults.cache.accuracy,
                               defaults.cache.theta_strata,
                               defaults.cache.phi_strata,
                               defaults.light_samples,
                               defaults.pixel_samples,
                               defaults.preferred_pixel_samples};
  if (quality == "standard") return standard;
  if (quality == "draft") return {"draft", 0.6f, 8, 16, 4, 1, 1};
  if (quality == "final") return {"final", 0.15f, defaults.cache.theta_strata, defaults.cache.phi_strata, 64, 0, 16};
  throw Error("--quality " + quality + ": unknown preset (use draft, standard or final)");
}

}  // namespace

void apply_quality(const std::string& quality, RenderSettings& s, const std::function<bool(const char*)>& given) {
  const QualityPreset p = quality_preset(quality);
  if (!given("--accuracy")) s.cache.accuracy = p.accuracy;
  if (!given("--hemisphere")) {
    s.cache.theta_strata = p.theta_strata;
    s.cache.phi_strata = p.phi_strata;
  }
  if (!given("--light-samples")) s.light_samples = p.light_samples;
  if (!given("--pixel-samples")) {
    s.pixel_samples = p.pixel_samples;
    s.preferred_pixel_samples = p.preferred_pixel_samples;
  }
}

std::string quality_preset_description(const std::string& quality) {
  const QualityPreset p = quality_preset(quality);
  char text[200];
  const std::string pixels =
      p.pixel_samples == 1 ? "one sample a pixel"
      : p.pixel_samples    ? std::to_string(p.pixel_samples) + " samples a pixel"
                           : "up to " + std::to_string(p.preferred_pixel_samples) + " samples a pixel where the frame allows";
  std::snprintf(text, sizeof text, "accuracy %g, %ux%u rays a record, %s, %u light samples", double(p.accuracy),
                p.theta_strata, p.phi_strata, pixels.c_str(), p.light_samples);
  return text;
}

std::string quality_summary(const std::string& quality, const RenderSettings& s) {
  const QualityPreset p = quality_preset(quality);
  char text[240];
  // The values the request holds, the preset's unless an option was given: the summary must not claim the preset's.
  std::snprintf(text, sizeof text, "%s: accuracy %g, %ux%u rays a record, %u light samples, %s pixel samples%s", p.name,
                double(s.cache.accuracy), s.cache.theta_strata, s.cache.phi_strata, s.light_samples,
                s.pixel_samples ? std::to_string(s.pixel_samples).c_str()
                                : ("up to " + std::to_string(s.preferred_pixel_samples)).c_str(),
                s.cache.accuracy != p.accuracy || s.cache.theta_strata != p.theta_strata ||
                        s.cache.phi_strata != p.phi_strata || s.light_samples != p.light_samples ||
                        s.pixel_samples != p.pixel_samples
                    ? " (options given replace the preset's)"
                    : "");
  return text;
}

}  // namespace rcsplat
