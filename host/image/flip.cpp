// LDR-FLIP as published (HPG 2020, section 4 and its supplement): a colour pipeline (contrast sensitivity filters in
// YCxCz, Hunt-adjusted L*a*b*, the HyAB distance, redistributed) and a feature pipeline (edges and points of the
// luminance), combined per pixel as colour^(1 - feature). Every filter FLIP uses is a sum of separable Gaussians or a
// Gaussian derivative, so each runs as two 1-D passes; borders repeat the edge pixel, as NVIDIA's implementation does.
#include "image/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "util/colour.h"
#include "util/error.h"

namespace rcsplat {
namespace {


using Vec3 = std::array<double, 3>;

// Linear sRGB (D65) to CIE XYZ and back.
constexpr double kRgbToXyz[3][3] = {{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                                    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                                    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
constexpr double kXyzToRgb[3][3] = {{3.241003275, -1.537398934, -0.498615861},
                                    {-0.969224334, 1.875930071, 0.041554224},
                                    {0.055639423, -0.204011202, 1.057148933}};

Vec3 multiply(const double m[3][3], const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// The white point: XYZ of linear RGB (1, 1, 1).
Vec3 white() { return multiply(kRgbToXyz, {1.0, 1.0, 1.0}); }


// YCxCz: L*a*b* without the cube root, the opponent space in which FLIP applies its contrast sensitivity functions.
Vec3 xyz_to_ycxcz(const Vec3& xyz) {
  const Vec3 w = white();
  const double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 ycxcz_to_xyz(const Vec3& v) {
  const Vec3 w = white();
  const double y = (v[0] + 16.0) / 116.0;
  return {(y + v[1] / 500.0) * w[0], y * w[1], (y - v[2] / 200.0) * w[2]};
}

// CIE L*a*b* with Hunt's adjustment (a and b scaled by 0.01 L): chroma matters less in the dark.
Vec3 hunt_lab(const Vec3& linear_rgb) {
  const Vec3 xyz = multiply(kRgbToXyz, linear_rgb), w = white();
  const double delta = 6.0 / 29.0, delta3 = delta * delta * delta;
  auto f = [&](double t) { return t > delta3 ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0; };
  const double fx = f(xyz[0] / w[0]), fy = f(xyz[1] / w[1]), fz = f(xyz[2] / w[2]);
  const double l = 116.0 * fy - 16.0;
  return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

double hyab(const Vec3& a, const Vec3& b) {
  return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// A 1-D filter applied along x then y (or y then x: they commute), clamping at the borders.
struct Plane {
  int width = 0, height = 0;
  std::vector<double> v;
  double& at(int x, int y) { return v[size_t(y) * size_t(width) + size_t(x)]; }
  double at(int x, int y) const { return v[size_t(y) * size_t(width) + size_t(x)]; }
};

Plane convolve(const Plane& in, const std::vector<double>& along_x, const std::vector<double>& along_y) {
  const int rx = int(along_x.size() / 2), ry = int(along_y.size() / 2);
  Plane rows{in.width, in.height, std::vector<double>(in.v.size())}, out = rows;
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      double s = 0.0;
      for (int k = -rx; k <= rx; ++k) s += along_x[size_t(k + rx)] * in.at(std::clamp(x + k, 0, in.width - 1), y);
      rows.at(x, y) = s;
    }
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      double s = 0.0;
      for (int k = -ry; k <= ry; ++k) s += along_y[size_t(k + ry)] * rows.at(x, std::clamp(y + k, 0, in.height - 1));
      out.at(x, y) = s;
    }
  return out;
}

// The contrast sensitivity filter of one opponent channel: a·sqrt(π/b)·exp(−π² r² / b) summed over one or two terms
// (r in degrees), normalised to unit sum over FLIP's common square support.
struct CsfTerm {
  double a, b;
};

Plane csf_filter(const Plane& channel, const std::vector<CsfTerm>& terms, double ppd) {
  const double widest = 0.04;  // the largest b of all three channels sets everyone's support, as in the paper
  const int radius = int(std::ceil(3.0 * std::sqrt(widest / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
  double total = 0.0;
  std::vector<std::vector<double>> gaussians;
  std::vector<double> weights;
  for (const CsfTerm& t : terms) {
    std::vector<double> g(size_t(2 * radius + 1));
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
      const double x = double(i) / ppd;
      g[size_t(i + radius)] = std::exp(-std::numbers::pi * std::numbers::pi * x * x / t.b);
      sum += g[size_t(i + radius)];
    }
    const double w = t.a * std::sqrt(std::numbers::pi / t.b);
    total += w * sum * sum;  // the 2-D kernel's sum: the product of its two 1-D sums
    gaussians.push_back(std::move(g));
    weights.push_back(w);
  }
  Plane out{channel.width, channel.height, std::vector<double>(channel.v.size(), 0.0)};
  for (size_t t = 0; t < terms.size(); ++t) {
    Plane part = convolve(channel, gaussians[t], gaussians[t]);
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += weights[t] / total * part.v[i];
  }
  return out;
}

// FLIP's edge (first derivative of a Gaussian) or point (second derivative) detector along x, with its positive and
// negative weights each normalised to sum to ±1; the kernel along the other axis is the plain Gaussian, unit sum.
void detector_kernels(double ppd, bool points, std::vector<double>& derivative, std::vector<double>& gaussian) {
  const double sigma = 0.5 * 0.082 * ppd;
  const int radius = int(std::ceil(3.0 * sigma));
  derivative.assign(size_t(2 * radius + 1), 0.0);
  gaussian.assign(size_t(2 * radius + 1), 0.0);
  double positive = 0.0, negative = 0.0, sum = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    const double x = double(i), g = std::exp(-x * x / (2.0 * sigma * sigma));
    const double d = points ? (x * x / (sigma * sigma) - 1.0) * g : -x * g;
    gaussian[size_t(i + radius)] = g;
    derivative[size_t(i + radius)] = d;
    sum += g;
    (d > 0 ? positive : negative) += d;
  }
  for (double& d : derivative) d = d > 0 ? d / positive : d / -negative;
  for (double& g : gaussian) g /= sum;
}

// Per pixel, the magnitude of the detector's response along x and along y.
Plane feature_magnitude(const Plane& luminance, const std::vector<double>& derivative,
                        const std::vector<double>& gaussian) {
  Plane dx = convolve(luminance, derivative, gaussian), dy = convolve(luminance, gaussian, derivative);
  for (size_t i = 0; i < dx.v.size(); ++i) dx.v[i] = std::hypot(dx.v[i], dy.v[i]);
  return dx;
}

struct Prepared {
  std::array<Plane, 3> ycxcz;  // opponent channels, for the colour pipeline
  Plane luminance;             // Y / Y_white in [0, 1], for the feature pipeline
};

Prepared prepare(const std::vector<float>& srgb, int width, int height) {
  const size_t n = size_t(width) * size_t(height);
  Prepared p;
  for (Plane& c : p.ycxcz) c = {width, height, std::vector<double>(n)};
  p.luminance = {width, height, std::vector<double>(n)};
  for (size_t i = 0; i < n; ++i) {
    Vec3 rgb;
    for (int c = 0; c < 3; ++c) {
      const float v = srgb[3 * i + size_t(c)];
      rgb[size_t(c)] = srgb_to_linear(std::clamp(std::isfinite(v) ? double(v) : 0.0, 0.0, 1.0));
    }
    const Vec3 ycxcz = xyz_to_ycxcz(multiply(kRgbToXyz, rgb));
    for (int c = 0; c < 3; ++c) p.ycxcz[size_t(c)].v[i] = ycxcz[size_t(c)];
    p.luminance.v[i] = (ycxcz[0] + 16.0) / 116.0;
  }
  return p;
}

// The colour pipeline's output per pixel: CSF-filtered, back to linear RGB clamped to the display, Hunt L*a*b*.
std::vector<Vec3> filtered_lab(const Prepared& p, double ppd) {
  static const std::array<std::vector<CsfTerm>, 3> channel_terms = {
      std::vector<CsfTerm>{{1.0, 0.0047}},                  // achromatic
      std::vector<CsfTerm>{{1.0, 0.0053}},                  // red-green
      std::vector<CsfTerm>{{34.1, 0.04}, {13.5, 0.025}}};  // blue-yellow
  std::array<Plane, 3> filtered;
  for (size_t c = 0; c < 3; ++c) filtered[c] = csf_filter(p.ycxcz[c], channel_terms[c], ppd);
  std::vector<Vec3> lab(p.luminance.v.size());
  for (size_t i = 0; i < lab.size(); ++i) {
    Vec3 rgb = multiply(kXyzToRgb, ycxcz_to_xyz({filtered[0].v[i], filtered[1].v[i], filtered[2].v[i]}));
    for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
    lab[i] = hunt_lab(rgb);
  }
  return lab;
}

}  // namespace

FlipResult ldr_flip(const std::vector<float>& reference_srgb, const std::vector<float>& test_srgb, int width, int height,
                    double pixels_per_degree) {
  const size_t n = size_t(width) * size_t(height);
  if (width < 1 || height < 1 || reference_srgb.size() != 3 * n || test_srgb.size() != 3 * n)
    throw Error("FLIP: the images are not both " + std::to_string(width) + "x" + std::to_string(height) + " RGB");
  const double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5;
  // The largest colour difference FLIP expects: Hunt-adjusted green against blue.
  const double cmax = std::pow(hyab(hunt_lab({0.0, 1.0, 0.0}), hunt_lab({0.0, 0.0, 1.0})), qc);

  const Prepared ref = prepare(reference_srgb, width, height), test = prepare(test_srgb, width, height);
  const std::vector<Vec3> ref_lab = filtered_lab(ref, pixels_per_degree), test_lab = filtered_lab(test, pixels_per_degree);

  std::vector<double> edge_d, edge_g, point_d, point_g;
  detector_kernels(pixels_per_degree, false, edge_d, edge_g);
  detector_kernels(pixels_per_degree, true, point_d, point_g);
  const Plane ref_edges = feature_magnitude(ref.luminance, edge_d, edge_g);
  const Plane test_edges = feature_magnitude(test.luminance, edge_d, edge_g);
  const Plane ref_points = feature_magnitude(ref.luminance, point_d, point_g);
  const Plane test_points = feature_magnitude(test.luminance, point_d, point_g);

  FlipResult result;
  result.error.resize(n);
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    // Colour: HyAB^qc, compressed above pc·cmax so that large differences do not swamp the map.
    const double e = std::pow(hyab(ref_lab[i], test_lab[i]), qc);
    const double colour = e < pc * cmax ? pt / (pc * cmax) * e : pt + (e - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
    const double feature =
        std::pow(std::max(std::abs(ref_edges.v[i] - test_edges.v[i]), std::abs(ref_points.v[i] - test_points.v[i])) /
                     std::sqrt(2.0),
                 qf);
    const double flip = std::pow(colour, 1.0 - feature);
    result.error[i] = float(flip);
    sum += flip;
  }
  result.mean = sum / double(n);
  return result;
}

std::vector<float> flip_heatmap(const std::vector<float>& error) {
  // matplotlib's magma (CC0), sampled at 17 points and interpolated linearly.
  static const std::array<std::array<float, 3>, 17> magma = {{
      {0.001f, 0.000f, 0.014f}, {0.040f, 0.031f, 0.134f}, {0.113f, 0.065f, 0.277f}, {0.212f, 0.062f, 0.419f},
      {0.317f, 0.072f, 0.485f}, {0.415f, 0.110f, 0.505f}, {0.513f, 0.148f, 0.508f}, {0.614f, 0.182f, 0.499f},
      {0.716f, 0.215f, 0.475f}, {0.817f, 0.256f, 0.436f}, {0.904f, 0.320f, 0.388f}, {0.961f, 0.418f, 0.360f},
      {0.987f, 0.536f, 0.382f}, {0.996f, 0.654f, 0.446f}, {0.997f, 0.770f, 0.535f}, {0.992f, 0.884f, 0.640f},
      {0.987f, 0.991f, 0.750f}}};
  std::vector<float> rgb(error.size() * 3);
  for (size_t p = 0; p < error.size(); ++p) {
    const float t = std::clamp(std::isfinite(error[p]) ? error[p] : 1.0f, 0.0f, 1.0f) * float(magma.size() - 1);
    const size_t i = std::min(size_t(t), magma.size() - 2);
    const float f = t - float(i);
    for (size_t c = 0; c < 3; ++c) rgb[3 * p + c] = magma[i][c] * (1 - f) + magma[i + 1][c] * f;
  }
  return rgb;
}

}  // namespace rcsplat
