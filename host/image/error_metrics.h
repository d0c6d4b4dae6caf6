// Image error against a reference (docs/ALGORITHM.md section 10): relMSE = mean (x - ref)^2 / (ref^2 + 0.01), RMSE, mean
// absolute error, over every channel of every pixel. The +0.01 ties relMSE to the scene's radiance scale: state the
// scene and exposure with every threshold.
#pragma once
#include <vector>

namespace rcsplat {

// The offset in relMSE's denominator, in the image's radiance units.
constexpr double kRelMseOffset = 0.01;

struct ErrorMetrics {
  double rel_mse = 0, rmse = 0, mae = 0;
};

ErrorMetrics image_error(const std::vector<float>& image, const std::vector<float>& reference);

// relMSE of block means: image and reference (RGB, width x height) averaged over block x block pixels, whole blocks
// only, then compared as image_error does. Averaging takes out noise and leaves in a cache's low-frequency error
// (blotches), which per-pixel relMSE flatters.
double block_rel_mse(const std::vector<float>& image, const std::vector<float>& reference, int width, int height,
                     int block);
// The block relMSE a path-traced reference's own noise adds on average, from its per-pixel variance of the mean
// (independent pixels): subtract it from a block relMSE measured against that reference.
double block_rel_mse_of_noise(const std::vector<float>& variance, const std::vector<float>& reference, int width,
                              int height, int block);

// Per-pixel relMSE (mean over the three channels), for heat maps and regional statistics.
std::vector<double> pixel_rel_mse(const std::vector<float>& image, const std::vector<float>& reference);

// A false-colour map of per-pixel relMSE on a log scale from 1e-6 (dark blue) to 1 (white), as display RGB.
std::vector<float> error_heatmap(const std::vector<double>& pixel_error);

}  // namespace rcsplat
