#include "image/error_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "util/error.h"

namespace rcsplat {

ErrorMetrics image_error(const std::vector<float>& image, const std::vector<float>& reference) {
  if (image.size() != reference.size() || image.empty()) throw Error("images of different sizes cannot be compared");
  ErrorMetrics m;
  for (size_t i = 0; i < image.size(); ++i) {
    double x = image[i], r = reference[i];
    if (!std::isfinite(x) || !std::isfinite(r)) throw Error("non-finite pixel value at channel index " + std::to_string(i));
    double d = x - r;
    m.rel_mse += d * d / (r * r + kRelMseOffset);
    m.rmse += d * d;
    m.mae += std::abs(d);
  }
  double n = double(image.size());
  m.rel_mse /= n;
  m.rmse = std::sqrt(m.rmse / n);
  m.mae /= n;
  return m;
}

std::vector<double> pixel_rel_mse(const std::vector<float>& image, const std::vector<float>& reference) {
  if (image.size() != reference.size()) throw Error("images of different sizes cannot be compared");
  std::vector<double> e(image.size() / 3);
  for (size_t p = 0; p < e.size(); ++p) {
    double sum = 0;
    for (size_t c = 0; c < 3; ++c) {
      double r = reference[3 * p + c], d = double(image[3 * p + c]) - r;
      sum += d * d / (r * r + kRelMseOffset);
    }
    e[p] = sum / 3.0;
  }
  return e;
}

std::vector<float> error_heatmap(const std::vector<double>& pixel_error) {
  // Dark blue, blue, green, yellow, red, white at 1e-6, 1e-5, ..., 1.
  static const std::array<std::array<float, 3>, 7> ramp = {{{0.0f, 0.0f, 0.15f}, {0.0f, 0.2f, 0.8f},
                                                           {0.0f, 0.7f, 0.3f}, {0.9f, 0.9f, 0.0f},
                                                           {1.0f, 0.4f, 0.0f}, {0.9f, 0.0f, 0.0f},
                                                           {1.0f, 1.0f, 1.0f}}};
  std::vector<float> rgb(pixel_error.size() * 3);
  for (size_t p = 0; p < pixel_error.size(); ++p) {
    double t = std::clamp((std::log10(std::max(pixel_error[p], 1e-12)) + 6.0), 0.0, 6.0);
    size_t i = std::min<size_t>(size_t(t), ramp.size() - 2);
    float f = float(t - double(i));
    for (size_t c = 0; c < 3; ++c) rgb[3 * p + c] = ramp[i][c] * (1 - f) + ramp[i + 1][c] * f;
  }
  return rgb;
}

}  // namespace rcsplat
