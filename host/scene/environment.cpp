#include "scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "util/colour.h"


namespace rcsplat {

std::string format_rgb(const glm::vec3& c) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(c.x), double(c.y), double(c.z));
  return text;
}

double environment_row_solid_angle(int row, int height) {
  const double pi = std::numbers::pi;
  return 2.0 * pi * (std::cos(pi * row / height) - std::cos(pi * (row + 1) / height));
}

std::string Environment::describe() const {
  if (!present()) return "none";
  if (source.empty()) return "uniform sky " + format_rgb(radiance[0]);
  char text[160];
  std::snprintf(text, sizeof text, " (%d x %d, intensity %g, rotated %g degrees)", width, height, double(intensity),
                double(rotation_degrees));
  return source + text;
}

PackedEnvironment pack_environment(const Environment& e) {
  PackedEnvironment p;
  if (!e.present()) {
    p.texels.assign(4, 0.0f);  // the kernels always get a buffer
    p.cdf.assign(1, 0.0f);
    return p;
  }
  const int w = e.width, h = e.height;
  p.width = unsigned(w);
  p.height = unsigned(h);
  const double radians = double(e.rotation_degrees) * (std::numbers::pi / 180.0);
  p.rotation[0] = float(std::cos(radians));
  p.rotation[1] = float(std::sin(radians));

  // The mean luminance over the sphere, weighted by solid angle, sets the peak's threshold.
  double power = 0.0;
  for (int j = 0; j < h; ++j) {
    double row = 0.0;
    for (int i = 0; i < w; ++i) row += luminance(e.radiance[size_t(j) * w + i]);
    power += row * environment_row_solid_angle(j, h) / w;
  }
  p.mean_luminance = power / (4.0 * std::numbers::pi);
  const double threshold = kEnvironmentPeakOverMean * p.mean_luminance;

  // Texels: the smooth fraction keeps each texel's luminance at most the threshold; the peak its excess.
  std::vector<double> peak_weight(size_t(w) * h);  // peak luminance times solid angle
  p.texels.resize(size_t(w) * h * 4);
  double peak_power = 0.0;
  for (int j = 0; j < h; ++j) {
    const double texel_solid_angle = environment_row_solid_angle(j, h) / w;
    for (int i = 0; i < w; ++i) {
      const size_t t = size_t(j) * w + i;
      const glm::vec3 c = e.radiance[t];
      const double lum = luminance(c);
      const float smooth = lum > threshold ? float(threshold / lum) : 1.0f;
      p.texels[4 * t + 0] = c.x;
      p.texels[4 * t + 1] = c.y;
      p.texels[4 * t + 2] = c.z;
      p.texels[4 * t + 3] = smooth;
      // The luminance the kernel will see for the peak (float, as it computes it), so its density matches.
      const glm::vec3 peak = c * (1.0f - smooth);
      peak_weight[t] = std::max(0.0, luminance(peak)) * texel_solid_angle;
      peak_power += peak_weight[t];
    }
  }
  p.peak_fraction = power > 0.0 ? peak_power / power : 0.0;
  if (!(peak_power > 0.0)) {
    p.cdf.assign(1, 0.0f);
    return p;
  }
  p.peak_power = float(peak_power);

  // The marginal CDF over rows, then each row's CDF over its texels; a row without peak is never chosen.
  p.cdf.assign(size_t(h + 1) + size_t(h) * size_t(w + 1), 0.0f);
  std::vector<double> row_weight(size_t(h), 0.0);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) row_weight[j] += peak_weight[size_t(j) * w + i];
    float* row = p.cdf.data() + (h + 1) + size_t(j) * (w + 1);
    double running = 0.0;
    for (int i = 0; i < w; ++i) {
      running += peak_weight[size_t(j) * w + i];
      row[i + 1] = row_weight[j] > 0.0 ? float(running / row_weight[j]) : float(i + 1) / float(w);
    }
    row[w] = 1.0f;
  }
  double running = 0.0;
  for (int j = 0; j < h; ++j) {
    running += row_weight[j];
    p.cdf[j + 1] = float(running / peak_power);
  }
  p.cdf[h] = 1.0f;
  return p;
}

}  // namespace rcsplat
