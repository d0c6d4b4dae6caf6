// LDR-FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild: "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020): a perceptual difference between two display images, per pixel in [0, 1]. It sees
// what relMSE does not: a colour shift, a lost edge, a blotch the eye picks out. rcsplat computes it itself so that
// `compare` and `sweep` need nothing beyond the renderer; benchmarks/flip_check.py checks it against NVIDIA's
// flip-evaluator package.
#pragma once
#include <numbers>
#include <vector>

namespace rcsplat {

// Pixels per degree of visual angle for FLIP's default viewer: 0.7 m from a 0.7 m wide, 3840-pixel-wide display.
constexpr double kFlipDefaultPixelsPerDegree = 0.7 * (3840.0 / 0.7) * (std::numbers::pi / 180.0);

struct FlipResult {
  std::vector<float> error;  // per pixel, row-major
  double mean = 0.0;
};

// Both images are sRGB-encoded display values in [0, 1] (values outside are clamped), RGB interleaved, width x height.
FlipResult ldr_flip(const std::vector<float>& reference_srgb, const std::vector<float>& test_srgb, int width, int height,
                    double pixels_per_degree = kFlipDefaultPixelsPerDegree);

// FLIP's per-pixel error in its customary colour map (magma, dark = no difference), as display RGB.
std::vector<float> flip_heatmap(const std::vector<float>& error);

}  // namespace rcsplat
