// Issue 10 part 3, leaks and thin geometry: records must not carry light through a thin wall or around a slat, must
// still see light that comes through a gap, and must hold their radius clamps into a sharp concave corner. Each case
// compares region means of the cache's indirect layer with a path-traced reference; the tolerances add three of the
// reference's standard errors (from its per-pixel variance) to the stated bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "render/renderer.h"
#include "test_support.h"

namespace rcsplat {
namespace {

using Region = std::function<bool(const glm::vec3& position, const glm::vec3& normal)>;

struct RegionMeans {
  double cache = 0, reference = 0, reference_sigma = 0;  // means of the indirect luminance over the region's pixels
  size_t pixels = 0;
};

struct CacheAndReference {
  RenderedImage cache, reference;

  RegionMeans means(const Region& inside) const {
    RegionMeans m;
    double variance = 0;
    for (size_t p = 0; p < cache.triangle.size(); ++p) {
      if (cache.triangle[p] < 0) continue;
      glm::vec3 x(cache.position[3 * p], cache.position[3 * p + 1], cache.position[3 * p + 2]);
      glm::vec3 n(cache.normal[3 * p], cache.normal[3 * p + 1], cache.normal[3 * p + 2]);
      if (!inside(x, n)) continue;
      for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(cache.indirect[3 * p + c]) && cache.indirect[3 * p + c] >= 0.0f);
        m.cache += cache.indirect[3 * p + c] / 3.0;
        m.reference += reference.indirect[3 * p + c] / 3.0;
        variance += reference.indirect_variance[3 * p + c] / 9.0;
      }
      ++m.pixels;
    }
    if (m.pixels) {
      m.cache /= double(m.pixels);
      m.reference /= double(m.pixels);
      m.reference_sigma = std::sqrt(variance) / double(m.pixels);
    }
    return m;
  }
};

CacheAndReference render_both(const Scene& scene, int size, unsigned reference_samples) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = size;
  settings.light_samples = 1;
  CacheAndReference r;
  r.cache = render(test::gpu(), scene, settings);
  settings.gi = GiMethod::path;
  settings.path.samples = reference_samples;
  settings.path.pixel_area = false;  // the points the cache shades: the wall's pixel columns are the same ones
  r.reference = render(test::gpu(), scene, settings);
  return r;
}

void add_box(Scene& s, glm::vec3 lo, glm::vec3 hi, uint32_t material) {
  glm::vec3 c[8];
  for (int i = 0; i < 8; ++i) c[i] = {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) s.add_quad(c[f[0]], c[f[1]], c[f[2]], c[f[3]], material);
}

SceneCamera looking_down(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfov) {
  SceneCamera camera;
  camera.eye = eye;
  camera.target = target;
  camera.up = up;
  camera.yfov = yfov;
  camera.aspect = 1.0f;
  return camera;
}

// A floor split by a wall 1 cm thick and 1 m high, with a strong light on one side (x < 0) and a gap of 0.4 m at
// one end (z > 0.6), seen from above so that both sides hold records. On the other side a second wall (x = 1.2) is
// lit through the gap and lights that side's floor. The floor just behind the thin wall, away from the gap, gets
// only that second wall's light: what a record from the lit side adds there is a leak. Records on the lit side
// that reached across (their footprint is at least three pixels, the wall a fraction of one) carried light over,
// and the dark side's records darkened the lit side by 29%, until records kept a horizon (kernels/cache_math.h).
TEST(Leaks, ThinWallKeepsItsLightAndTheGapLetsItThrough) {
  Scene s;
  s.source = "thin wall with a gap";
  s.materials.push_back({"grey", glm::vec4(0.6f, 0.6f, 0.6f, 1.0f), -1, glm::vec3(0.0f), false});
  s.add_quad({-2, 0, -1}, {-2, 0, 1}, {2, 0, 1}, {2, 0, -1}, 0);
  add_box(s, {-0.005f, 0.0f, -1.0f}, {0.005f, 1.0f, 0.6f}, 0);
  add_box(s, {1.2f, 0.0f, -1.0f}, {1.21f, 1.0f, 1.0f}, 0);
  SceneLight light;
  light.position = {-0.3f, 0.5f, 0.8f};
  light.intensity = glm::vec3(50.0f);
  s.lights.push_back(light);
  s.cameras.push_back(looking_down({0.0f, 3.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 0.75f));
  const CacheAndReference r = render_both(s, 96, 1024);
  auto floor = [](float x_lo, float x_hi, float z_lo, float z_hi) {
    return [=](const glm::vec3& x, const glm::vec3& n) {
      return n.y > 0.9f && x.y < 1e-3f && x.x > x_lo && x.x < x_hi && x.z > z_lo && x.z < z_hi;
    };
  };
  const RegionMeans lit = r.means(floor(-0.1f, -0.005f, -0.9f, 0.3f));
  const RegionMeans behind = r.means(floor(0.005f, 0.1f, -0.9f, 0.3f));
  const RegionMeans gap = r.means(floor(0.3f, 1.15f, 0.3f, 1.0f));
  std::printf("lit side %.4f (ref %.4f), behind the wall %.5f (ref %.5f +- %.5f), through the gap %.4f (ref %.4f)\n",
              lit.cache, lit.reference, behind.cache, behind.reference, behind.reference_sigma, gap.cache,
              gap.reference);
  ASSERT_GT(lit.pixels, 50u);
  ASSERT_GT(behind.pixels, 50u);
  ASSERT_GT(gap.pixels, 50u);
  ASSERT_GT(gap.reference, 0.01 * lit.reference) << "the scene lets light through the gap";
  // The dark side's records must not darken the lit side (they did, by 29%): within 5%.
  EXPECT_NEAR(lit.cache, lit.reference, 0.05 * lit.reference + 3.0 * lit.reference_sigma);
  // Light through the wall: below 1% of the lit side's indirect light.
  EXPECT_LT(behind.cache - behind.reference, 0.01 * lit.reference + 3.0 * behind.reference_sigma);
  // The gap's light is not missed: within 10% of the reference.
  EXPECT_NEAR(gap.cache, gap.reference, 0.1 * gap.reference + 3.0 * gap.reference_sigma);
}

// Concave corners of 90 and 10 degrees: a floor and a plane rising from it along x = 0, lit from above. Near the
// apex Ward's harmonic distance goes to zero and only the radius clamps hold records together; the region within
// 5 cm of the apex must match the reference within 10% and show no seam (no pixel beyond three times the reference's
// largest value there).
void check_corner(float degrees) {
  Scene s;
  s.source = "concave corner";
  s.materials.push_back({"grey", glm::vec4(0.6f, 0.6f, 0.6f, 1.0f), -1, glm::vec3(0.0f), false});
  s.add_quad({0, 0, -1}, {0, 0, 1}, {1.5f, 0, 1}, {1.5f, 0, -1}, 0);
  const float a = degrees * float(M_PI) / 180.0f;
  const glm::vec3 up_the_slope(std::cos(a), std::sin(a), 0.0f);
  s.add_quad({0, 0, -1}, 1.5f * up_the_slope + glm::vec3(0, 0, -1), 1.5f * up_the_slope + glm::vec3(0, 0, 1), {0, 0, 1},
             0);
  SceneLight light;
  // Above the 90-degree corner; inside the 10-degree wedge (at a tenth of the slope's height near its open end), so
  // that both planes are lit up to the apex.
  light.position = degrees > 45.0f ? glm::vec3(0.9f, 1.6f, 0.3f) : glm::vec3(1.2f, 0.1f * 1.2f * std::tan(a), 0.3f);
  light.intensity = glm::vec3(5.0f);
  s.lights.push_back(light);
  // Into the wedge along its bisector, from outside it.
  const glm::vec3 bisector(std::cos(0.5f * a), std::sin(0.5f * a), 0.0f);
  s.cameras.push_back(looking_down(glm::vec3(0.0f, 0.0f, 0.0f) + 1.2f * bisector + glm::vec3(0.0f, 0.0f, 0.9f),
                                   {0.02f, 0.002f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.8f));
  const CacheAndReference r = render_both(s, 80, 1024);
  auto near_apex = [](const glm::vec3& x, const glm::vec3&) { return glm::length(glm::vec2(x.x, x.y)) < 0.05f; };
  const RegionMeans apex = r.means(near_apex);
  double seam = 0, reference_peak = 0;
  for (size_t p = 0; p < r.cache.triangle.size(); ++p) {
    glm::vec3 x(r.cache.position[3 * p], r.cache.position[3 * p + 1], r.cache.position[3 * p + 2]);
    if (r.cache.triangle[p] < 0 || !near_apex(x, x)) continue;
    seam = std::max(seam, double(r.cache.indirect[3 * p + 1]));
    reference_peak = std::max(reference_peak, double(r.reference.indirect[3 * p + 1]));
  }
  std::printf("%g degrees: %zu pixels within 5 cm of the apex, cache %.4f, reference %.4f +- %.5f; largest %.4f "
              "(reference %.4f); %llu records\n",
              degrees, apex.pixels, apex.cache, apex.reference, apex.reference_sigma, seam, reference_peak,
              (unsigned long long)r.cache.stats.irradiance.records);
  ASSERT_GT(apex.pixels, 30u);
  EXPECT_NEAR(apex.cache, apex.reference, 0.1 * apex.reference + 3.0 * apex.reference_sigma) << degrees << " degrees";
  EXPECT_LT(seam, 3.0 * reference_peak) << degrees << " degrees";
}

TEST(Leaks, ConcaveCornerOfNinetyDegrees) { check_corner(90.0f); }
TEST(Leaks, ConcaveCornerOfTenDegrees) { check_corner(10.0f); }

// Slats a centimetre thick, 10 cm apart, under a light: their tops are lit, their undersides see only the lit tops of
// the slats below and the floor. A camera below and to the side sees undersides beside the front edges: no light
// from a slat's own lit top may reach its underside (opposite normals: Ward's weight and the normal test), so the
// undersides' indirect light must not exceed the reference's by more than 10%. (It is 12% below it at the default
// a = 0.3 and 1.6% below at a = 0.1: interpolation error where the irradiance varies fast, not a leak.)
TEST(Leaks, CentimetreSlatsKeepTheirLitTopsOffTheirUndersides) {
  Scene s;
  s.source = "slats";
  s.materials.push_back({"grey", glm::vec4(0.6f, 0.6f, 0.6f, 1.0f), -1, glm::vec3(0.0f), false});
  s.add_quad({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0);
  for (int i = 0; i < 5; ++i) {
    float y = 0.3f + 0.1f * float(i);
    add_box(s, {-0.6f, y, -0.6f + 0.25f * float(i)}, {0.6f, y + 0.01f, -0.3f + 0.25f * float(i)}, 0);
  }
  SceneLight light;
  light.position = {0.2f, 2.0f, -0.4f};
  light.intensity = glm::vec3(20.0f);
  s.lights.push_back(light);
  s.cameras.push_back(looking_down({0.0f, 0.2f, 1.4f}, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.9f));
  const CacheAndReference r = render_both(s, 96, 1024);
  const RegionMeans undersides =
      r.means([](const glm::vec3& x, const glm::vec3& n) { return n.y < -0.9f && x.y > 0.25f; });
  std::printf("undersides: %zu pixels, cache %.5f, reference %.5f +- %.5f\n", undersides.pixels, undersides.cache,
              undersides.reference, undersides.reference_sigma);
  ASSERT_GT(undersides.pixels, 100u);
  EXPECT_LT(undersides.cache, 1.1 * undersides.reference + 3.0 * undersides.reference_sigma);
}

// Records on both sides of one two-sided sheet of zero thickness: a tent folded from a single sheet, lit from outside,
// seen at its open end so that the outside of one side and the inside of the other meet along the ridge in the image.
// The inside, lit only through the open ends, must not take light from the outside's records (within 5% of the
// reference; the outside too). Planted: without the normal's part in Ward's weight and the facing test, the inside
// comes out 7.4% bright.
TEST(Leaks, BothSidesOfATwoSidedSheet) {
  Scene s;
  s.source = "tent";
  s.materials.push_back({"grey", glm::vec4(0.6f, 0.6f, 0.6f, 1.0f), -1, glm::vec3(0.0f), false});
  s.materials.push_back({"sheet", glm::vec4(0.7f, 0.7f, 0.7f, 1.0f), -1, glm::vec3(0.0f), true});
  s.add_quad({-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, 0);
  const glm::vec3 ridge_back(0, 1, -1), ridge_front(0, 1, 1);
  for (float side : {-1.0f, 1.0f}) {
    glm::vec3 foot_back(0.7f * side, 0, -1), foot_front(0.7f * side, 0, 1);
    s.add_quad(ridge_back, ridge_front, foot_front, foot_back, 1);
  }
  SceneLight light;
  light.position = {-2.0f, 2.5f, 0.5f};
  light.intensity = glm::vec3(30.0f);
  s.lights.push_back(light);
  s.cameras.push_back(looking_down({-0.9f, 0.75f, 2.6f}, {0.2f, 0.55f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.8f));
  const CacheAndReference r = render_both(s, 96, 1024);
  // The left side's outside faces up and left (normal x < 0); the right side's inside faces down and left too, but
  // down: the two sides of the same sheet differ in the sign of the normal's y.
  auto on_sheet = [](const glm::vec3& x, const glm::vec3&) { return x.y > 0.05f && std::abs(x.z) < 0.95f; };
  const RegionMeans outside =
      r.means([&](const glm::vec3& x, const glm::vec3& n) { return on_sheet(x, n) && n.y > 0.3f; });
  const RegionMeans inside =
      r.means([&](const glm::vec3& x, const glm::vec3& n) { return on_sheet(x, n) && n.y < -0.3f; });
  std::printf("outside %zu pixels %.4f (ref %.4f), inside %zu pixels %.4f (ref %.4f +- %.4f)\n", outside.pixels,
              outside.cache, outside.reference, inside.pixels, inside.cache, inside.reference, inside.reference_sigma);
  ASSERT_GT(outside.pixels, 100u);
  ASSERT_GT(inside.pixels, 100u);
  EXPECT_NEAR(outside.cache, outside.reference, 0.05 * outside.reference + 3.0 * outside.reference_sigma);
  EXPECT_NEAR(inside.cache, inside.reference, 0.05 * inside.reference + 3.0 * inside.reference_sigma);
}

}  // namespace
}  // namespace rcsplat
