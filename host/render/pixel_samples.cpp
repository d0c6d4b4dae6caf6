#include "render/pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/camera.h"
#include "render/renderer.h"
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

RenderedImage render(GpuContext& gpu, const Scene& scene, const RenderSettings& requested) {
  RenderSettings settings = requested;
  int width = settings.width, height = settings.height;
  resolve_resolution(choose_camera(scene, settings.camera, settings.camera_overrides), width, height);
  if (settings.pixel_samples == 0) settings.pixel_samples = default_pixel_samples(settings, width, height);
  const unsigned side = pixel_sample_side(settings.pixel_samples);
  // Path tracing over the pixel's area traces rounds of the output frame itself (renderer.cpp).
  if (side == 1 || (settings.gi == GiMethod::path && settings.path.pixel_area))
    return render_single_sample(gpu, scene, settings);
  if (std::max(width, height) * int(side) > 16384)
    throw Error("--pixel-samples " + std::to_string(settings.pixel_samples) + " at " + std::to_string(width) + "x" +
                std::to_string(height) + " needs a sub-pixel frame above 16384 pixels wide or high");
  // The sub-pixel frame, its layers gathered into output pixels on the device (passes/layer_pass.h).
  RenderedImage out = render_single_sample(gpu, scene, sub_pixel_settings(settings, width, height, side));
  const unsigned n = side * side;
  out.stats.pixel_samples = n;
  out.stats.light_samples *= n;
  out.stats.path_samples *= n;
  return out;
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
