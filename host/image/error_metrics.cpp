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

namespace {

// Sums of each whole block x block block of an RGB image, per channel: [block index * 3 + channel].
std::vector<double> block_sums(const std::vector<float>& rgb, int width, int height, int block) {
  if (block < 1 || rgb.size() != size_t(width) * size_t(height) * 3)
    throw Error("block error: the image is not " + std::to_string(width) + "x" + std::to_string(height) + " RGB");
  const int bw = width / block, bh = height / block;
  std::vector<double> sums(size_t(bw) * size_t(bh) * 3, 0.0);
  for (int y = 0; y < bh * block; ++y)
    for (int x = 0; x < bw * block; ++x)
      for (int c = 0; c < 3; ++c)
        sums[(size_t(y / block) * bw + size_t(x / block)) * 3 + c] += rgb[(size_t(y) * width + x) * 3 + c];
  return sums;
}

}  // namespace

double block_rel_mse(const std::vector<float>& image, const std::vector<float>& reference, int width, int height,
                     int block) {
  std::vector<double> a = block_sums(image, width, height, block), r = block_sums(reference, width, height, block);
  if (a.empty()) throw Error("block error: the image is smaller than one block");
  const double area = double(block) * double(block);
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    double x = a[i] / area, ref = r[i] / area, d = x - ref;
    sum += d * d / (ref * ref + kRelMseOffset);
  }
  return sum / double(a.size());
}

double block_rel_mse_of_noise(const std::vector<float>& variance, const std::vector<float>& reference, int width,
                              int height, int block) {
  std::vector<double> v = block_sums(variance, width, height, block), r = block_sums(reference, width, height, block);
  if (v.empty()) throw Error("block error: the image is smaller than one block");
  const double area = double(block) * double(block);
  double sum = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    double ref = r[i] / area;
    sum += (v[i] / (area * area)) / (ref * ref + kRelMseOffset);  // variance of a mean of independent pixels
  }
  return sum / double(v.size());
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
