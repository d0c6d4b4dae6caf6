// Anti-aliasing (--pixel-samples N): each pixel is an s x s grid of sub-pixels (N = s^2), each cell's point moved so
// that the N points form a rotated grid (kernels/gbuffer.cl: N different columns and rows, so near-vertical and
// near-horizontal edges are resolved in steps of 1/N of the pixel, not 1/s; the same for every method, so a reference
// can integrate the very points a cache render shades). The frame is rendered s times larger and its layers are
// gathered back on the device (passes/layer_pass.h: light, albedo, normal, irradiance, coverage, records reaching a
// pixel averaged; records sitting in it summed; position, depth and triangle of sub-pixel (s / 2, s / 2), a single
// surface); records stay in world space.
#pragma once
#include "render/frame.h"
#include "render/settings.h"

namespace rcsplat {

// --pixel-samples left to rcsplat (0, the command line's default): settings.preferred_pixel_samples (renders 4, a 2 x 2
// grid: anti-aliased edges at about 1.2x one sample's time, records are one sample's; references 16), else the next
// smaller of 16, 4, 1 that the path samples divide by and whose sub-pixel frame stays within kMaxDefaultSubPixels.
constexpr unsigned kReferencePixelSamples = 16;
constexpr double kMaxDefaultSubPixels = 16.0 * 1024 * 1024;
unsigned default_pixel_samples(const RenderSettings& settings, int width, int height);

// The side s of the sub-pixel grid; throws rcsplat::Error unless N is 1, 4, 9, 16, ... (up to 64).
unsigned pixel_sample_side(unsigned pixel_samples);

// Light and path samples per output pixel divided among its n sub-pixels (or rounds): light samples rounded up, at
// least one each; path samples must divide evenly (throws rcsplat::Error naming --spp and --pixel-samples).
RenderSettings samples_per_sub_pixel(const RenderSettings& settings, unsigned n);

// The light-sample strata a pixel's direct light takes (kernels/direct.cl): sqrt(samples) rounded up, squared.
unsigned light_sample_strata(unsigned light_samples);

// "jittered" where path tracing integrates over the pixel's area (PathSettings::pixel_area), else "rotated grid" (at
// one sample a pixel, its centre; files written before the rotated grid say "centres"): the EXR attribute
// rcsplat:pixel_points, the JSON's pixel_points, and what --resume compares.
const char* pixel_points_name(const RenderSettings& settings);

// The settings of the s-times larger frame: light samples and path samples divided among the sub-pixels (path samples
// must divide evenly), record reach and placement spacing in sub-pixels so that records keep their world-space size,
// and placement stopping one output pixel apart.
RenderSettings sub_pixel_settings(const RenderSettings& settings, int width, int height, unsigned side);

}  // namespace rcsplat
