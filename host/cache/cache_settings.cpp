#include "cache/cache_settings.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "util/error.h"

namespace rcsplat {
namespace {

std::string number(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(v));
  return text;
}

void check_hemisphere(const char* option, unsigned m, unsigned n) {
  if (m < 1 || m > HEMISPHERE_MAX_THETA_STRATA || n < 1 || n > HEMISPHERE_MAX_PHI_STRATA)
    throw Error(std::string(option) + " MxN: M must be 1.." + std::to_string(HEMISPHERE_MAX_THETA_STRATA) +
                " and N 1.." + std::to_string(HEMISPHERE_MAX_PHI_STRATA) + " (given " + std::to_string(m) + "x" +
                std::to_string(n) + ")");
}

}  // namespace

void validate_cache_settings(const CacheSettings& c) {
  if (!(c.accuracy >= kMinAccuracy) || !(c.accuracy <= kMaxAccuracy))
    throw Error("--accuracy must be between " + number(kMinAccuracy) + " and " + number(kMaxAccuracy) + " (given " +
                number(c.accuracy) + ")");
  check_hemisphere("--hemisphere", c.theta_strata, c.phi_strata);
  if ((c.fine_theta_strata == 0) != (c.fine_phi_strata == 0))
    throw Error("--fine-hemisphere MxN: give both M and N");
  if (c.fine_theta_strata) check_hemisphere("--fine-hemisphere", c.fine_theta_strata, c.fine_phi_strata);
  if (!(c.min_reach_pixels > 0.0f) || !(c.max_reach_pixels >= c.min_reach_pixels) || !std::isfinite(c.max_reach_pixels))
    throw Error("--spacing MIN,MAX: need 0 < MIN <= MAX, in pixels");
  if (!(c.adaptive_error >= 0.0f) || !std::isfinite(c.adaptive_error))
    throw Error("--adaptive-rays must be 0 (off) or positive (given " + number(c.adaptive_error) + ")");
  if (!(c.hessian_error >= 0.0f) || !std::isfinite(c.hessian_error))
    throw Error("--hessian-error must be 0 (the split sphere) or positive (given " + number(c.hessian_error) + ")");
  if (c.guide_rays > kMaxGuideRays)
    throw Error("--guide-rays must be between 0 and " + std::to_string(kMaxGuideRays) + " (given " +
                std::to_string(c.guide_rays) + ")");
  if (c.placement_lines < 0)
    throw Error("--placement-lines must be 0 (off) or a height in lines (given " + std::to_string(c.placement_lines) +
                ")");
  if (c.coarsest_spacing_pixels < 1) throw Error("the coarsest placement spacing must be at least 1 pixel");
  if (c.finest_spacing_pixels < 1 || c.finest_spacing_pixels > c.coarsest_spacing_pixels)
    throw Error("the finest placement spacing must be between 1 pixel and the coarsest");
}

void scale_placement_to_image(CacheSettings& cache, int height) {
  if (cache.placement_lines <= 0 || height <= cache.placement_lines) return;
  const double scale = double(height) / double(cache.placement_lines);
  cache.min_reach_pixels = float(double(cache.min_reach_pixels) * scale);
  cache.max_reach_pixels = float(double(cache.max_reach_pixels) * scale);
  cache.finest_spacing_pixels = std::max(1, int(std::lround(double(cache.finest_spacing_pixels) * scale)));
  cache.coarsest_spacing_pixels =
      std::max(cache.finest_spacing_pixels, int(std::lround(double(cache.coarsest_spacing_pixels) * scale)));
}

HemisphereParams hemisphere_params(const CacheSettings& c, unsigned seed, int spacing) {
  bool fine = spacing <= c.finest_spacing_pixels && c.fine_theta_strata > 0;
  HemisphereParams hp{};
  hp.theta_strata = fine ? c.fine_theta_strata : c.theta_strata;
  hp.phi_strata = fine ? c.fine_phi_strata : c.phi_strata;
  hp.seed = seed;
  hp.min_radius_pixels = c.min_reach_pixels / c.accuracy;
  hp.max_radius_pixels = c.max_reach_pixels / c.accuracy;
  hp.hessian_error = c.hessian_error;
  return hp;
}

float min_radius_pixels(const CacheSettings& c) { return c.min_reach_pixels / c.accuracy; }
float max_radius_pixels(const CacheSettings& c) { return c.max_reach_pixels / c.accuracy; }

unsigned largest_theta_strata(const CacheSettings& c) { return std::max(c.theta_strata, c.fine_theta_strata); }

int coarsest_placement_spacing(const CacheSettings& c) {
  int coarsest = 1;
  while (coarsest * 2 <= c.coarsest_spacing_pixels) coarsest *= 2;
  return coarsest;
}

}  // namespace rcsplat
