// Anti-aliasing (--pixel-samples, render/pixel_samples.h): an edge pixel's value is its covered fraction, against the
// exact area of the pixel's square on the lit side of the edge; bad counts are refused.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/pixel_samples.h"
#include "render/renderer.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

// The area of the square [x0, x1] x [y0, y1] below the line y = k x + d, by clipping the square (Sutherland-Hodgman
// against one half-plane) and the shoelace formula.
double area_below(double x0, double x1, double y0, double y1, double k, double d) {
  const double square[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  auto inside = [&](const double* p) { return p[1] <= k * p[0] + d; };
  std::vector<std::array<double, 2>> kept;
  for (int i = 0; i < 4; ++i) {
    const double* a = square[i];
    const double* b = square[(i + 1) % 4];
    if (inside(a)) kept.push_back({a[0], a[1]});
    if (inside(a) != inside(b)) {
      // Where a-b crosses the line: a + t (b - a) with a.y + t (b.y - a.y) = k (a.x + t (b.x - a.x)) + d.
      const double t = (k * a[0] + d - a[1]) / ((b[1] - a[1]) - k * (b[0] - a[0]));
      kept.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
    }
  }
  double twice = 0.0;
  for (size_t i = 0; i < kept.size(); ++i) {
    const auto& p = kept[i];
    const auto& q = kept[(i + 1) % kept.size()];
    twice += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * std::abs(twice);
}

// An emitter of radiance 1, the quad a-b-c-d of the plane z = 0, seen by an orthographic camera whose view is
// [-1, 1]^2 of that plane.
Scene lamp_under_orthographic_camera(const char* name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  Scene s;
  s.source = name;
  s.materials.push_back({"lamp", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), -1, glm::vec3(1.0f), false});
  s.add_quad(a, b, c, d, 0);
  SceneCamera cam;
  cam.orthographic = true;
  cam.eye = {0.0f, 0.0f, 5.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.xmag = cam.ymag = 1.0f;
  cam.aspect = 1.0f;
  s.cameras.push_back(cam);
  return s;
}

// The emitter below the slanted line y = 0.3 x + 0.1.
Scene slanted_edge() {
  return lamp_under_orthographic_camera("slanted edge", {-3.0f, -3.0f, 0.0f}, {3.0f, -3.0f, 0.0f}, {3.0f, 1.0f, 0.0f},
                                        {-3.0f, -0.8f, 0.0f});
}

struct EdgeError {
  double mean_abs = 0.0, max_abs = 0.0, mean_signed = 0.0;
  size_t pixels = 0;
};

// How far each pixel the edge crosses is from its covered fraction.
EdgeError edge_error(unsigned pixel_samples) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 32;
  settings.gi = GiMethod::none;
  settings.pixel_samples = pixel_samples;
  const RenderedImage image = render(test::gpu(), slanted_edge(), settings);
  EdgeError e;
  const double size = 2.0 / settings.width;
  for (int y = 0; y < settings.height; ++y) {
    for (int x = 0; x < settings.width; ++x) {
      const double x0 = -1.0 + x * size, y1 = 1.0 - y * size;
      const double covered = area_below(x0, x0 + size, y1 - size, y1, 0.3, 0.1) / (size * size);
      if (covered <= 1e-6 || covered >= 1.0 - 1e-6) continue;
      const double error = image.emission[3 * (size_t(y) * settings.width + x)] - covered;
      e.mean_abs += std::abs(error);
      e.mean_signed += error;
      e.max_abs = std::max(e.max_abs, std::abs(error));
      ++e.pixels;
    }
  }
  e.mean_abs /= double(e.pixels);
  e.mean_signed /= double(e.pixels);
  return e;
}

// With s x s sub-pixels, one in each cell of the grid, a straight edge is off by at most about one sub-pixel column's
// share of the pixel, 1 / s, and by much less on average; one sample a pixel gives 0 or 1, off by a quarter on average
// (the jagged edge). Signed errors cancel along the edge: the image's total is right to within a few hundredths of a
// pixel per edge pixel. This edge's slope, 0.3, lies near the rows of the 4 x 4 rotated grid (14 degrees), its worst
// case: 0.021 mean at 16 samples against the cells' centres' 0.013; over all orientations the two are equal.
TEST(PixelSamples, EdgePixelsHoldTheirCoveredFraction) {
  const EdgeError one = edge_error(1);
  ASSERT_GT(one.pixels, 30u);
  EXPECT_GT(one.mean_abs, 0.15) << "one sample a pixel cannot be anti-aliased";
  for (unsigned n : {4u, 16u}) {
    const EdgeError e = edge_error(n);
    const double side = std::sqrt(double(n));
    EXPECT_EQ(e.pixels, one.pixels);
    EXPECT_LE(e.max_abs, 1.0 / side + 1e-6) << n << " samples";
    EXPECT_LT(e.mean_abs, 0.4 / side) << n << " samples";
    EXPECT_LT(std::abs(e.mean_signed), 0.05) << n << " samples";
  }
}

// The emitter right of the vertical line x = -1 + (16 + into) / 16: at 32 pixels across, the line lies `into` of a
// pixel into column 16, which is 1 - into covered.
Scene vertical_edge(float into = 0.1f) {
  const float edge = -1.0f + (16.0f + into) / 16.0f;
  return lamp_under_orthographic_camera("vertical edge", {edge, -3.0f, 0.0f}, {3.0f, -3.0f, 0.0f}, {3.0f, 3.0f, 0.0f},
                                        {edge, 3.0f, 0.0f});
}

// Column 16's mean value less its covered fraction 0.9, path traced with 16 pixel samples.
double column_error(bool pixel_area) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 32;
  settings.gi = GiMethod::path;
  settings.bounces = 1;
  settings.path.samples = 16;
  settings.pixel_samples = 16;
  settings.path.pixel_area = pixel_area;
  const RenderedImage image = render(test::gpu(), vertical_edge(), settings);
  double sum = 0.0;
  for (int y = 0; y < settings.height; ++y) sum += image.emission[3 * (size_t(y) * settings.width + 16)];
  EXPECT_EQ(image.emission[3 * 15], 0.0f);
  EXPECT_EQ(image.emission[3 * 17], 1.0f);
  return sum / settings.height - 0.9;
}

// Path tracing integrates over the pixel's area (PathSettings::pixel_area): the edge lies 0.1 pixel into column 16,
// where a random point of each cell converges to 0.9. Its tolerance, from the variance: the four cells the edge
// crosses are lit with probability 0.6, so a pixel's variance is 4 (1/16)^2 0.6 * 0.4 = 3.75e-3 and the column's mean
// over 32 pixels has a standard deviation of 0.011; four of them is 0.044. The fixed points of a cache render (the
// rotated grid, kernels/gbuffer.cl) sit at x = (k + 1/2) / 16, k = 0 .. 15, of which the first two lie left of 0.1:
// 14/16 lit, off by exactly -0.025 in every pixel (the cells' centres, at x = 1/8, 3/8, ..., were off by +0.1).
TEST(PixelSamples, PathTracingIntegratesOverThePixelsArea) {
  const double jittered = column_error(true), grid = column_error(false);
  std::printf("column 16 less its covered fraction: random points of the cells %+.4f, the rotated grid %+.4f\n",
              jittered, grid);
  EXPECT_LT(std::abs(jittered), 0.044);
  EXPECT_NEAR(grid, 14.0 / 16.0 - 0.9, 1e-6);
}

// A cache render's sub-pixels (and --sub-pixel-grid's) sit on a rotated grid (kernels/gbuffer.cl): at 4 samples their
// x within the pixel are 1/8, 3/8, 5/8 and 7/8, so an edge 0.3 of a pixel into column 16 (0.7 covered) leaves three of
// four lit, 0.75 in every row, where the cells' centres (x = 1/4, 3/4) gave 0.5. Exact: four sub-pixels of 0 or 1.
TEST(PixelSamples, RotatedGridResolvesNearVerticalEdges) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 32;
  settings.gi = GiMethod::none;
  settings.pixel_samples = 4;
  const RenderedImage image = render(test::gpu(), vertical_edge(0.3f), settings);
  for (int y = 0; y < settings.height; ++y) {
    EXPECT_EQ(image.emission[3 * (size_t(y) * settings.width + 15)], 0.0f) << "row " << y;
    EXPECT_EQ(image.emission[3 * (size_t(y) * settings.width + 16)], 0.75f) << "row " << y;
    EXPECT_EQ(image.emission[3 * (size_t(y) * settings.width + 17)], 1.0f) << "row " << y;
  }
}

TEST(PixelSamples, CountsThatAreNotSquaresOrDoNotDivideTheSamplesAreRefused) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 8;
  settings.gi = GiMethod::none;
  settings.pixel_samples = 3;
  EXPECT_THROW(render(test::gpu(), slanted_edge(), settings), Error);
  settings.pixel_samples = 4;
  settings.gi = GiMethod::path;
  settings.path.samples = 6;
  EXPECT_THROW(render(test::gpu(), slanted_edge(), settings), Error);
  settings.path.samples = 8;
  const RenderedImage image = render(test::gpu(), slanted_edge(), settings);
  EXPECT_EQ(image.width, 8);
  EXPECT_EQ(image.stats.path.samples, 8u);
  EXPECT_EQ(image.stats.primary.pixel_samples, 4u);
}

// --pixel-samples left out: 4 for renders, 16 for references (a finer grid than the render's), fewer where the path
// samples do not divide by them or the sub-pixel frame would be too large.
TEST(PixelSamples, DefaultsAreFourForRendersAndSixteenForReferences) {
  RenderSettings render_settings = test::one_bounce_one_sample();
  EXPECT_EQ(default_pixel_samples(render_settings, 512, 384), 4u);
  RenderSettings reference = test::one_bounce_one_sample();
  reference.gi = GiMethod::path;
  reference.preferred_pixel_samples = kReferencePixelSamples;
  reference.path.samples = 1024;
  EXPECT_EQ(default_pixel_samples(reference, 1024, 768), 16u);
  EXPECT_EQ(default_pixel_samples(reference, 2048, 1536), 4u);  // 16 would be 50 M sub-pixels
  reference.path.samples = 8;
  EXPECT_EQ(default_pixel_samples(reference, 512, 384), 4u);
  reference.path.samples = 6;
  EXPECT_EQ(default_pixel_samples(reference, 512, 384), 1u);
  EXPECT_EQ(default_pixel_samples(render_settings, 16384, 8), 1u);  // a side above 16384 sub-pixels
}

}  // namespace
}  // namespace rcsplat
