// The flicker metric (issue 42, item 4) on sequences with a known answer: identical frames read 0, independent noise
// reads its relative variance, and a smooth world-space pattern seen by a moving camera reads almost nothing once
// reprojected (and much more if it were not). Frames are made on the host: a plane y = 0 seen by a pinhole camera.
#include "image/flicker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "image/error_metrics.h"
#include "util/error.h"

namespace rcsplat {
namespace {

ViewCamera look(glm::dvec3 eye, glm::dvec3 target, double yfov_degrees) {
  char text[200];
  std::snprintf(text, sizeof text,
                "perspective eye %.17g,%.17g,%.17g target %.17g,%.17g,%.17g up 0,1,0 "
                "yfov_degrees %.17g ymag 0",
                eye.x, eye.y, eye.z, target.x, target.y, target.z, yfov_degrees);
  return parse_view_camera(text, "test");
}

// Each pixel's ray through its centre onto the plane y = 0 (within |x|, |z| < 6), shaded by `shade`.
template <typename Shade>
SequenceFrame frame_of_plane(const ViewCamera& c, int w, int h, Shade shade) {
  SequenceFrame f;
  f.width = w;
  f.height = h;
  f.camera = c;
  f.rgb.assign(size_t(w) * size_t(h) * 3, 0.0f);
  f.position.assign(size_t(w) * size_t(h) * 3, 0.0f);
  f.depth.assign(size_t(w) * size_t(h), 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double sx = (2.0 * (x + 0.5) / w - 1.0) * c.tan_half_fov_y * w / h;
      const double sy = (1.0 - 2.0 * (y + 0.5) / h) * c.tan_half_fov_y;
      const glm::dvec3 d = glm::normalize(c.forward + sx * c.right + sy * c.up);
      const double t = -c.eye.y / d.y;
      const glm::dvec3 p = c.eye + t * d;
      if (!(t > 0.0) || std::fabs(p.x) > 6.0 || std::fabs(p.z) > 6.0) continue;
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      f.depth[i] = float(t);
      for (int k = 0; k < 3; ++k) {
        f.position[3 * i + size_t(k)] = float(p[k]);
        f.rgb[3 * i + size_t(k)] = float(shade(p, k));
      }
    }
  return f;
}

TEST(Flicker, IdenticalFramesReadZero) {
  const ViewCamera c = look({0.5, 3.0, 5.0}, {0.0, 0.0, 0.0}, 40.0);
  const SequenceFrame f =
      frame_of_plane(c, 64, 48, [](const glm::dvec3& p, int k) { return 0.3 + 0.1 * k + 0.2 * std::sin(3 * p.x); });
  const TemporalError e = temporal_rel_mse(f, f);
  EXPECT_EQ(e.rel_mse, 0.0);
  EXPECT_EQ(e.pixels, e.hits);
  EXPECT_GT(e.pixels, 64u * 48u / 2);
}

// Independent noise of standard deviation s around c in every frame reads s^2 / (c^2 + 0.01). Tolerance: the mean's
// sampling error (sqrt(2 / N), under 1% for these N) plus the denominator's own noise (the mean of two noisy values
// in place of c: about +1.5% here), so 4%.
TEST(Flicker, IndependentNoiseReadsItsRelativeVariance) {
  const ViewCamera c = look({0.0, 4.0, 4.0}, {0.0, 0.0, 0.0}, 50.0);
  const double mean = 0.5, sigma = 0.05;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, sigma);
  double sum = 0.0;
  const int pairs = 4;
  SequenceFrame earlier = frame_of_plane(c, 64, 64, [&](const glm::dvec3&, int) { return mean + noise(rng); });
  for (int i = 0; i < pairs; ++i) {
    SequenceFrame later = frame_of_plane(c, 64, 64, [&](const glm::dvec3&, int) { return mean + noise(rng); });
    sum += temporal_rel_mse(earlier, later).rel_mse;
    earlier = std::move(later);
  }
  const double expected = sigma * sigma / (mean * mean + kRelMseOffset);
  EXPECT_NEAR(sum / pairs, expected, 0.04 * expected);
}

// A pattern fixed on the plane, the camera moving: reprojected, only the nearest pixel's offset (under half a pixel
// footprint, about 0.03 units here and more at grazing angles, on a pattern of slope at most 0.24) remains; compared
// pixel to pixel (the bug this guards against), the camera's motion shows as flicker over 10 times larger (16 here).
TEST(Flicker, AMovingCameraOverAStillPatternReadsAlmostNothing) {
  auto pattern = [](const glm::dvec3& p, int k) { return 0.5 + 0.2 * std::sin(1.2 * p.x + k) * std::cos(0.8 * p.z); };
  const SequenceFrame before = frame_of_plane(look({0.0, 3.0, 5.0}, {0.0, 0.0, 0.0}, 40.0), 96, 72, pattern);
  SequenceFrame after = frame_of_plane(look({0.3, 3.1, 4.9}, {0.1, 0.0, 0.0}, 40.0), 96, 72, pattern);
  const TemporalError moved = temporal_rel_mse(before, after);
  EXPECT_GT(double(moved.pixels), 0.8 * double(moved.hits));
  EXPECT_LT(moved.rel_mse, 1e-4);
  SequenceFrame unprojected = after;
  unprojected.camera = before.camera;  // as if the camera had not moved: pixel p compared with pixel p
  unprojected.position = before.position;
  unprojected.depth = before.depth;
  EXPECT_GT(temporal_rel_mse(before, unprojected).rel_mse, 10.0 * moved.rel_mse);
}

// Light that does not change, seen through a texture: the texture makes the nearest pixel read a little flicker; over
// the albedo (--demodulate) it reads none, and pixels too dark to divide are left out.
TEST(Flicker, OverTheAlbedoATextureUnderStillLightReadsNothing) {
  auto albedo = [](const glm::dvec3& p, int k) { return p.x > 0.5 ? 0.01 : 0.3 + 0.3 * std::sin(7.0 * p.z + k); };
  auto lit = [&](const glm::dvec3& p, int k) { return 0.7 * albedo(p, k); };
  const ViewCamera a = look({0.0, 3.0, 5.0}, {0.0, 0.0, 0.0}, 40.0), b = look({0.2, 3.0, 4.9}, {0.05, 0.0, 0.0}, 40.0);
  SequenceFrame before = frame_of_plane(a, 96, 72, lit), after = frame_of_plane(b, 96, 72, lit);
  const TemporalError textured = temporal_rel_mse(before, after);
  EXPECT_GT(textured.rel_mse, 1e-4);
  divide_by_albedo(before.rgb, frame_of_plane(a, 96, 72, albedo).rgb);
  divide_by_albedo(after.rgb, frame_of_plane(b, 96, 72, albedo).rgb);
  const TemporalError light = temporal_rel_mse(before, after);
  EXPECT_LT(light.rel_mse, 1e-12);
  EXPECT_LT(light.pixels, textured.pixels) << "the dark part (albedo 0.01) is left out";
  EXPECT_GT(light.pixels, textured.pixels / 4);
}

TEST(Flicker, AMalformedCameraAttributeIsRefused) {
  for (const char* bad :
       {"", "fisheye eye 0,0,0 target 0,0,1 up 0,1,0 yfov_degrees 40",
        "perspective eye 0,0 target 0,0,1 up 0,1,0 yfov_degrees 40",
        "perspective eye 0,0,0 target 0,0,0 up 0,1,0 yfov_degrees 40", "perspective eye 0,0,0 target 0,0,1 up 0,1,0",
        "orthographic eye 0,0,0 target 0,0,1 up 0,1,0 ymag 0"})
    EXPECT_THROW(parse_view_camera(bad, "f.exr"), Error) << bad;
}

}  // namespace
}  // namespace rcsplat
