#include "render/pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/camera.h"
#include "util/error.h"

namespace rcsplat {

unsigned pixel_sample_side(unsigned pixel_samples) {
  const unsigned side = unsigned(std::lround(std::sqrt(double(pixel_samples))));
  if (pixel_samples < 1 || side * side != pixel_samples || side > 8)
    throw Error("--pixel-samples " + std::to_string(pixel_samples) + ": must be a square number from 1 to 64 (1, 4, 9, "
                "16, ...): each pixel is a square grid of sub-pixels");
  return side;
}

unsigned default_pixel_samples(const RenderSettings& s, int width, int height) {
  for (unsigned n : {16u, 4u}) {
    const int side = int(pixel_sample_side(n));
    if (n > s.preferred_pixel_samples || (s.gi == GiMethod::path && s.path.samples % n)) continue;
    if (std::max(width, height) * side > 16384 || double(width) * double(height) * n > kMaxDefaultSubPixels) continue;
    return n;
  }
  return 1;
}

RenderSettings samples_per_sub_pixel(const RenderSettings& s, unsigned n) {
  RenderSettings sub = s;
  sub.light_samples = s.light_samples ? std::max(1u, (s.light_samples + n - 1) / n) : 0;
  if (s.gi == GiMethod::path) {
    if (s.path.samples % n)
      throw Error("--spp " + std::to_string(s.path.samples) + " must be a multiple of --pixel-samples " +
                  std::to_string(n) + ": each sub-pixel takes the same share");
    sub.path.samples = s.path.samples / n;
  }
  return sub;
}

unsigned light_sample_strata(unsigned light_samples) {
  return light_samples ? unsigned(std::ceil(std::sqrt(double(light_samples)))) : 0;
}

const char* pixel_points_name(const RenderSettings& settings) {
  return settings.gi == GiMethod::path && settings.path.pixel_area ? "jittered" : "rotated grid";
}

RenderSettings sub_pixel_settings(const RenderSettings& s, int width, int height, unsigned side) {
  RenderSettings sub = samples_per_sub_pixel(s, side * side);  // per output pixel, split among the sub-pixels
  sub.pixel_samples = 1;
  sub.sub_pixel_side = side;
  sub.width = width * int(side);
  sub.height = height * int(side);
  // Record reach and placement in sub-pixels: the same world-space records as at one sample.
  sub.cache.min_reach_pixels *= float(side);
  sub.cache.max_reach_pixels *= float(side);
  // The Hessian's radius is (C / lambda)^(1/4) footprints for lambda per footprint^2, so sqrt(footprint) * (C /
  // lambda_world)^(1/4) in world units: side^2 times C keeps it one output pixel's.
  sub.cache.hessian_error *= float(side * side);
  sub.cache.coarsest_spacing_pixels *= int(side);
  // Placement stops one output pixel apart, as at one sample: the records (and their rays) are one sample's, and
  // sub-pixels that none reaches (slivers along edges) take the best-weighted record near them.
  sub.cache.finest_spacing_pixels *= int(side);
  return sub;
}

}  // namespace rcsplat
