// The photon map of --bounce-method photons (kernels/photon_map.h): photons that land again after each reflection
// carry the flux it leaves, the estimates match a double-precision sum over the disc (with the scene's surface: a linear
// fit over the area the disc holds), and a lookup returns the nearest facing photon's estimates.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>
#include <set>

#include "bvh/bvh8.h"
#include "cache/photon_map.h"
#include "cl/device_scene.h"
#include "kernels/photon_grid.h"
#include "passes/grid_sort_pass.h"
#include "passes/light_guide_pass.h"
#include "passes/photon_landings_pass.h"
#include "passes/photon_map_pass.h"
#include "passes/surface_patch_pass.h"
#include "render/bounce_choice.h"
#include "scene/environment.h"
#include "closed_cube.h"
#include "gap_room_scene.h"
#include "render/renderer.h"
#include "pass_probe.h"
#include "test_support.h"

namespace rcsplat {
namespace {

constexpr double kPi = std::numbers::pi;

// The closed cube (albedo 0.5) lit by a point light of 3 cd.
Scene lit_closed_cube() {
  Scene s = test::closed_cube();
  s.lights.push_back({"point", LightType::point, {0.1f, 0.2f, -0.1f}, {0, 0, -1}, glm::vec3(3.0f)});
  return s;
}

// In a closed cube every photon lands again after each reflection, so landing k reflects the light's 4 pi I times
// albedo^(k + 1), exactly (each photon carries the same power).
TEST(PhotonMap, EachLandingCarriesTheFluxItsReflectionLeaves) {
  Scene scene = lit_closed_cube();
  Bvh8 bvh = build_bvh8(scene.positions);
  DeviceScene device(test::gpu(), scene, bvh);
  const unsigned photons = 1u << 14, landings = 3;
  std::vector<PhotonHit> hits = LightGuidePass(test::gpu(), device).shoot(photons, 7, landings);
  ASSERT_EQ(hits.size(), size_t(photons) * landings);
  for (unsigned k = 0; k < landings; ++k) {
    double sum = 0.0;
    size_t landed = 0;
    for (size_t i = k; i < hits.size(); i += landings) {
      landed += hits[i].hit != 0;
      sum += 0.2126 * hits[i].flux[0] + 0.7152 * hits[i].flux[1] + 0.0722 * hits[i].flux[2];
    }
    const double expected = 4.0 * kPi * 3.0 * std::pow(0.5, double(k + 1));
    EXPECT_EQ(landed, photons) << "landing " << k;
    EXPECT_NEAR(sum, expected, 1e-4 * expected) << "landing " << k;
    // What arrives is what the previous landing reflected (the light's power at landing 0).
    double arrived = 0.0;
    for (size_t i = k; i < hits.size(); i += landings)
      arrived += 0.2126 * hits[i].incident[0] + 0.7152 * hits[i].incident[1] + 0.0722 * hits[i].incident[2];
    EXPECT_NEAR(arrived, 2.0 * expected, 2e-4 * expected) << "landing " << k;
  }
  // The map keeps the landings after a reflection: the same photons' landings 1 and 2, all lit.
  std::vector<PhotonHit> reflected = LightGuidePass(test::gpu(), device).shoot(photons, 7, landings, 1);
  ASSERT_EQ(lit_landings(reflected).size(), size_t(photons) * (landings - 1));
  for (size_t i = 0; i < reflected.size(); ++i)
    ASSERT_EQ(reflected[i].flux[0], hits[(i / 2) * landings + 1 + i % 2].flux[0]) << "stored landing " << i;
}

// Random photons on a floor (y = 0, both sides) and a wall (x = 0) meeting it, with random flux.
struct RandomPhotons {
  std::vector<PhotonHit> photons;
  double area = 3.0;  // the floor's two sides and the wall's one, each 1 x 1
};

// The photon arrives with flux `flux` and its surface reflects `reflected` times it.
PhotonHit photon_at(float x, float y, float z, glm::vec3 n, glm::vec3 flux, float reflected = 0.5f) {
  PhotonHit p{};
  p.position[0] = x, p.position[1] = y, p.position[2] = z;
  p.normal[0] = n.x, p.normal[1] = n.y, p.normal[2] = n.z;
  p.incident[0] = flux.x, p.incident[1] = flux.y, p.incident[2] = flux.z;
  p.flux[0] = reflected * flux.x, p.flux[1] = reflected * flux.y, p.flux[2] = reflected * flux.z;
  p.hit = 1;
  return p;
}

RandomPhotons random_photons(unsigned count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  RandomPhotons out;
  for (unsigned i = 0; i < count; ++i) {
    glm::vec3 flux(u(rng), u(rng), u(rng));
    float a = u(rng), b = u(rng);
    switch (i % 3) {
      case 0: out.photons.push_back(photon_at(a, 0.0f, b, {0, 1, 0}, flux)); break;
      case 1: out.photons.push_back(photon_at(a, 0.0f, b, {0, -1, 0}, 0.5f * flux)); break;
      default: out.photons.push_back(photon_at(0.0f, a, b, {1, 0, 0}, 2.0f * flux)); break;
    }
  }
  return out;
}

glm::dvec3 position_of(const PhotonHit& p) { return {p.position[0], p.position[1], p.position[2]}; }
glm::dvec3 normal_of(const PhotonHit& p) { return {p.normal[0], p.normal[1], p.normal[2]}; }

// Each lookup photon's estimate against the sum, in double, of the flux of every photon within the radius and within
// PHOTON_DISC_HALF_THICKNESS r of the tangent plane on a surface facing the same way, over pi^2 r^2 (no surface
// patches: every disc is taken as full), leaving out the lookup photon itself, whose count the estimate carries too.
// Beside the floor and the wall, two shelves above the floor facing up, at 0.4 of
// the disc's half-thickness (within it: counted by the floor's estimates) and 1.7 times it (beyond: left out; no two
// surfaces lie exactly one half-thickness apart). Photons within 1e-5 r of the disc's rim or faces could fall either way
// in float: such estimates are skipped (counted). Tolerance 1e-4 relative (float sums of a few dozen terms). The
// photons carry landings 1 .. 3; the shallow estimates (a path continued one bounce past a short ray reads them) count
// only landings 1 and 2.
TEST(PhotonMap, EstimatesMatchADoublePrecisionSumOverTheDisc) {
  RandomPhotons given = random_photons(30000, 11);
  const double area = given.area + 2.0;  // and the two shelves' tops, 1 x 1 each
  const float expected_r = photon_gather_radius(area, given.photons.size() + 20000, 32);
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    float height = (i % 2 ? 0.4f : 1.7f) * PHOTON_DISC_HALF_THICKNESS * expected_r;
    glm::vec3 flux(u(rng), u(rng), u(rng));
    given.photons.push_back(photon_at(u(rng), height, u(rng), {0, 1, 0}, flux, u(rng)));
  }
  // Landings by i / 3, not i: random_photons picks the surface by i % 3.
  for (size_t i = 0; i < given.photons.size(); ++i) given.photons[i].landing = 1 + int(i / 3 % 3);
  PhotonMapGrids grids = build_photon_map(given.photons, area, 32, 4);
  grids.shallow_landings = 3;
  const double r = grids.all.params.radius, r2 = r * r;
  ASSERT_GT(r, 0.0);
  ASSERT_EQ(float(r), expected_r);
  PhotonMapPass pass(test::gpu(), grids);
  std::vector<cl_float4> estimates = test::PassProbe::photon_estimates(pass), shallow = test::PassProbe::shallow_photon_estimates(pass);
  ASSERT_EQ(estimates.size(), 2 * grids.lookup.photons.size());
  ASSERT_EQ(shallow.size(), 2 * grids.lookup.photons.size());
  size_t compared = 0, ambiguous = 0;
  double all_sum = 0.0, shallow_sum = 0.0;  // two landings in three count in the shallow estimates
  for (size_t i = 0; i < grids.lookup.photons.size(); ++i) {
    glm::dvec3 x = position_of(grids.lookup.photons[i]), n = normal_of(grids.lookup.photons[i]);
    glm::dvec3 flux(0.0), shallow_flux(0.0), incident(0.0), shallow_incident(0.0);
    bool rim = false, self = false;
    double support = 0.0;
    for (const PhotonHit& p : grids.all.photons) {
      glm::dvec3 d = position_of(p) - x;
      double d2 = glm::dot(d, d);
      if (glm::dot(normal_of(p), n) <= 0.5) continue;
      if (d2 == 0.0 && !self) {  // the lookup photon itself, left out of its own estimate
        self = true;
        continue;
      }
      double height = std::abs(glm::dot(d, n));
      const double half = PHOTON_DISC_HALF_THICKNESS * r;
      rim = rim || std::abs(d2 - r2) < 1e-5 * r2 || std::abs(height - half) < 1e-5 * r;
      if (d2 < r2 && height < half) {
        const glm::dvec3 reflected(p.flux[0], p.flux[1], p.flux[2]), arrived(p.incident[0], p.incident[1], p.incident[2]);
        flux += reflected;
        incident += arrived;
        support += 1.0;
        if (p.landing < 3) shallow_flux += reflected, shallow_incident += arrived;
      }
    }
    ASSERT_TRUE(self) << "photon " << i << " is not among all photons";
    if (rim) {
      ++ambiguous;
      continue;
    }
    ASSERT_EQ(estimates[2 * i].s[3], support) << "photon " << i << ": photons in its disc";
    // Reflected light and irradiance, each over pi, in the estimates' order (kernels/photon_map.cl).
    const glm::dvec3 expected[2] = {flux / (kPi * kPi * r2), incident / (kPi * kPi * r2)};
    const glm::dvec3 expected_shallow[2] = {shallow_flux / (kPi * kPi * r2), shallow_incident / (kPi * kPi * r2)};
    all_sum += expected[0].x;
    shallow_sum += expected_shallow[0].x;
    for (int k = 0; k < 2; ++k)
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(estimates[2 * i + k].s[c], expected[k][c], 1e-4 * expected[k][c] + 1e-9)
            << "photon " << i << " estimate " << k << " channel " << c;
        ASSERT_NEAR(shallow[2 * i + k].s[c], expected_shallow[k][c], 1e-4 * expected_shallow[k][c] + 1e-9)
            << "shallow, photon " << i << " estimate " << k << " channel " << c;
      }
    ++compared;
  }
  std::printf("compared %zu estimates, skipped %zu at the rim; shallow over all %.4f\n", compared, ambiguous,
              shallow_sum / all_sum);
  EXPECT_LT(ambiguous, compared / 100 + 1);
  EXPECT_NEAR(shallow_sum / all_sum, 2.0 / 3.0, 0.02);
}

// The estimate with the scene's surface, in double (kernels/photon_map.cl density_at_centre): the flux of the photons
// in the disc about x (normal n) and the area of the patches in it, their moments in the tangent plane, the linear fit
// with its ridge, and the clamp to [0, 2 mean]; the photon at x itself left out, and the plain mean where fewer than
// PHOTON_FIT_SUPPORT photons remain. incident: the arriving flux, else the reflected. *rim: a photon or
// patch lies within 1e-5 r^2 of the disc's rim (float may place it either way).
glm::dvec3 fitted_estimate(const PhotonMapGrids& grids, glm::dvec3 x, glm::dvec3 n, bool incident, bool* rim) {
  const double r2 = double(grids.all.params.radius) * grids.all.params.radius;
  const double half = PHOTON_DISC_HALF_THICKNESS * std::sqrt(r2);
  const glm::dvec3 t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, {1, 0, 0}) : glm::cross(n, {0, 1, 0}));
  const glm::dvec3 b = glm::cross(n, t);
  auto inside = [&](glm::dvec3 d, glm::dvec3 m) {
    *rim = *rim || std::abs(glm::dot(d, d) - r2) < 1e-5 * r2;
    return glm::dot(d, d) < r2 && std::abs(glm::dot(d, n)) < half && glm::dot(m, n) > 0.5;
  };
  glm::dvec3 sum(0.0), sx(0.0), sy(0.0);
  bool self = false;
  double support = 0.0;
  for (const PhotonHit& p : grids.all.photons) {
    glm::dvec3 d = position_of(p) - x;
    if (!inside(d, normal_of(p))) continue;
    if (glm::dot(d, d) == 0.0 && !self) {  // the photon itself
      self = true;
      continue;
    }
    support += 1.0;
    const float* f = incident ? p.incident : p.flux;
    glm::dvec3 flux(f[0], f[1], f[2]);
    sum += flux, sx += flux * glm::dot(d, t), sy += flux * glm::dot(d, b);
  }
  double area = 0.0, ax = 0.0, ay = 0.0, axx = 0.0, axy = 0.0, ayy = 0.0;
  for (const SurfacePatch& q : grids.patches.patches) {
    glm::dvec3 d = glm::dvec3(q.position[0], q.position[1], q.position[2]) - x;
    if (!inside(d, {q.normal[0], q.normal[1], q.normal[2]})) continue;
    double dx = glm::dot(d, t), dy = glm::dot(d, b);
    area += q.area, ax += q.area * dx, ay += q.area * dy;
    axx += q.area * dx * dx, axy += q.area * dx * dy, ayy += q.area * dy * dy;
  }
  area = std::max(area, double(PHOTON_MIN_AREA_SHARE) * kPi * r2);
  const glm::dvec3 mean = sum / area;
  if (support < double(PHOTON_FIT_SUPPORT)) return mean / kPi;  // too few photons to fit a slope to
  const double cx = ax / area, cy = ay / area, ridge = double(PHOTON_GRADIENT_RIDGE) * area * r2 / 4.0;
  const double mxx = axx - area * cx * cx + ridge, mxy = axy - area * cx * cy, myy = ayy - area * cy * cy + ridge;
  const double det = mxx * myy - mxy * mxy;
  const glm::dvec3 vx = sx - sum * cx, vy = sy - sum * cy;
  const glm::dvec3 gx = (myy * vx - mxy * vy) / det, gy = (mxx * vy - mxy * vx) / det;
  return glm::clamp(mean - (gx * cx + gy * cy), glm::dvec3(0.0), 2.0 * mean) / kPi;
}

// With the scene's surface (a unit floor, y = 0, and a wall, x = 0, as triangles): photons land on the floor with a
// density that grows along x, 0.2 + 4x, so the true irradiance there is linear, and uniformly on the wall. Every 32nd
// lookup photon's two estimates match fitted_estimate to 2e-3 of the mean (float sums over hundreds of photons and
// patches, and the fit's cancellations). Near the floor's edges x = 0 and x = 1, where the disc holds half a disc of
// floor whose light is dimmer (brighter) than at its centre, the plain estimate (flux over pi r^2) reads half the
// light and the area's mean alone ~4% off; the fitted estimates' mean over those photons is within 2.5% of the truth
// (its noise: about 1%, from the printed count and spread).
TEST(PhotonMap, EstimatesWithTheSceneSurfaceFitTheLightLinearlyToTheDiscsCentre) {
  const std::vector<glm::vec3> triangles = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {1, 0, 0},
                                            {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 0}, {0, 1, 1}, {0, 0, 1}};
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PhotonHit> photons;
  const int floor_photons = 60000;
  const float flux = 1.0f / floor_photons;  // the floor's photons carry 1 in all: mean irradiance 1
  for (int i = 0; i < floor_photons; ++i) {
    // x from density (0.2 + 4x) / 2.2, whose CDF (0.2 x + 2 x^2) / 2.2 = w: x = (-0.2 + sqrt(0.04 + 17.6 w)) / 4.
    double x = (-0.2 + std::sqrt(0.04 + 17.6 * u(rng))) / 4.0;
    photons.push_back(photon_at(float(x), 0.0f, float(u(rng)), {0, 1, 0}, glm::vec3(flux), 0.25f));
    if (i % 2) photons.push_back(photon_at(0.0f, float(u(rng)), float(u(rng)), {1, 0, 0}, glm::vec3(flux), 0.25f));
  }
  // 256 photons a disc on average: the edges' half discs hold over PHOTON_FIT_SUPPORT, and are fitted.
  PhotonMapGrids grids = build_photon_map(photons, 2.0, 256, 2, triangles);
  ASSERT_FALSE(grids.patches.patches.empty());
  PhotonMapPass pass(test::gpu(), grids);
  std::vector<cl_float4> estimates = test::PassProbe::photon_estimates(pass);
  const double r = grids.all.params.radius;
  size_t compared = 0, edge_count = 0;
  double edge_ratio = 0.0, edge_square = 0.0, plain_ratio = 0.0;
  for (size_t i = 0; i < grids.lookup.photons.size(); ++i) {
    const PhotonHit& p = grids.lookup.photons[i];
    glm::dvec3 x = position_of(p), n = normal_of(p);
    if (i % 32 == 0) {
      bool rim = false;
      glm::dvec3 expected[2] = {fitted_estimate(grids, x, n, false, &rim), fitted_estimate(grids, x, n, true, &rim)};
      if (!rim) {
        for (int k = 0; k < 2; ++k)
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(estimates[2 * i + k].s[c], expected[k][c], 2e-3 * expected[k][c] + 1e-9)
                << "photon " << i << " estimate " << k << " channel " << c;
        ++compared;
      }
    }
    const bool near_edge = n.y > 0.5 && (x.x < 0.5 * r || x.x > 1.0 - 0.5 * r) && x.z > r && x.z < 1.0 - r;
    if (near_edge) {
      const double truth = (0.2 + 4.0 * x.x) / 2.2 / kPi;  // irradiance over pi
      double plain = 0.0;
      for (const PhotonHit& q : grids.all.photons) {
        glm::dvec3 d = position_of(q) - x;
        if (glm::dot(d, d) < r * r && glm::dot(normal_of(q), n) > 0.5) plain += q.incident[0];
      }
      const double ratio = estimates[2 * i + 1].s[0] / truth;
      edge_ratio += ratio, edge_square += ratio * ratio, plain_ratio += plain / (kPi * kPi * r * r) / truth;
      ++edge_count;
      // The reflected estimate is the irradiance times the photons' 0.25, whatever the fit.
      ASSERT_NEAR(estimates[2 * i].s[0], 0.25 * estimates[2 * i + 1].s[0], 1e-5 * estimates[2 * i + 1].s[0] + 1e-9);
    }
  }
  ASSERT_GT(edge_count, 50u);
  const double mean = edge_ratio / double(edge_count);
  const double spread = std::sqrt(std::max(edge_square / double(edge_count) - mean * mean, 0.0));
  std::printf("compared %zu estimates; %zu at the floor's edges: fitted/true %.4f (spread %.3f), plain/true %.4f\n",
              compared, edge_count, mean, spread, plain_ratio / double(edge_count));
  EXPECT_GT(compared, 100u);
  EXPECT_NEAR(mean, 1.0, 0.025);
  EXPECT_LT(plain_ratio / double(edge_count), 0.75);  // what the fit repairs
}

// The nearest lookup photon within r of x on a surface facing n among those in x's bucket (index, or SIZE_MAX) and the
// nearest and second-nearest such distances among all lookup photons (double precision).
struct Nearest {
  size_t in_bucket = SIZE_MAX, overall = SIZE_MAX;
  double bucket_distance = INFINITY, bucket_second = INFINITY, distance = INFINITY, second = INFINITY;
};

Nearest nearest_photons(const PhotonGrid& grid, glm::dvec3 x, glm::dvec3 n) {
  const PhotonMapParams& m = grid.params;
  const uint32_t bucket = photon_bucket(photon_cell(float(x.x), m.grid_origin[0], m.cell_size),
                                        photon_cell(float(x.y), m.grid_origin[1], m.cell_size),
                                        photon_cell(float(x.z), m.grid_origin[2], m.cell_size), m.bucket_count);
  Nearest out;
  auto consider = [](size_t j, double d, size_t* best, double* nearest, double* second) {
    if (d < *nearest) {
      *second = *nearest;
      *nearest = d;
      *best = j;
    } else if (d < *second) {
      *second = d;
    }
  };
  for (size_t j = 0; j < grid.photons.size(); ++j) {
    if (glm::dot(normal_of(grid.photons[j]), n) <= 0.5) continue;
    double d = glm::length(position_of(grid.photons[j]) - x);
    consider(j, d, &out.overall, &out.distance, &out.second);
    if (j >= grid.bucket_starts[bucket] && j < grid.bucket_starts[bucket + 1] && d < m.radius)
      consider(j, d, &out.in_bucket, &out.bucket_distance, &out.bucket_second);
  }
  return out;
}

// A lookup at x returns the estimate of the nearest lookup photon within r on a surface facing the same way among
// those in x's own bucket; where there is none, that of the nearest within 0.45 r (half a cell, less a margin) if one
// is; no light when no facing photon lies within r. Checked exactly where no other photon is as near (to 1e-3) and x
// is not within 1e-4 cells of a cell wall (float division may round either way there); otherwise the result must be
// some facing photon's estimate within r, or no light. (Points on the planes lie exactly on a cell wall, as the
// photons do: an exact quotient rounds the same on both sides.)
TEST(PhotonMap, LookupReturnsTheNearestFacingPhotonsEstimate) {
  RandomPhotons given = random_photons(30000, 12);
  PhotonMapGrids grids = build_photon_map(given.photons, given.area, 32, 4);
  const PhotonMapParams& m = grids.lookup.params;
  const double r = m.radius;
  PhotonMapPass pass(test::gpu(), grids);
  std::vector<cl_float4> estimates = test::PassProbe::photon_estimates(pass);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-0.1f, 1.1f);
  std::vector<cl_float4> points, normals;
  const glm::vec3 facings[4] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}};  // the last faces no photon
  for (int i = 0; i < 4000; ++i) {
    float a = u(rng), b = u(rng);
    glm::vec3 n = facings[i % 4];
    glm::vec3 p = i % 4 == 2 ? glm::vec3(0.0f, a, b) : glm::vec3(a, 0.0f, b);
    points.push_back({{p.x, p.y, p.z, 0.0f}});
    normals.push_back({{n.x, n.y, n.z, 0.0f}});
  }
  std::vector<cl_float4> found = test::photon_radiance_at(test::gpu(), pass, points, normals);
  size_t own_bucket = 0, half_cell = 0, dark = 0, loose = 0;
  auto equals = [&](size_t i, size_t j) {
    return found[i].s[0] == estimates[2 * j].s[0] && found[i].s[1] == estimates[2 * j].s[1] &&
           found[i].s[2] == estimates[2 * j].s[2];
  };
  for (size_t i = 0; i < points.size(); ++i) {
    glm::dvec3 x(points[i].s[0], points[i].s[1], points[i].s[2]), n(normals[i].s[0], normals[i].s[1], normals[i].s[2]);
    bool near_wall = false;
    for (int a = 0; a < 3; ++a) {
      double f = (x[a] - m.grid_origin[a]) / m.cell_size;
      near_wall = near_wall || (f != std::round(f) && std::abs(f - std::round(f)) < 1e-4);
    }
    Nearest near = nearest_photons(grids.lookup, x, n);
    if (!near_wall && near.in_bucket != SIZE_MAX && near.bucket_second > near.bucket_distance * (1.0 + 1e-3)) {
      ASSERT_TRUE(equals(i, near.in_bucket)) << "point " << i << ": not the nearest in its own bucket";
      ++own_bucket;
    } else if (!near_wall && near.in_bucket == SIZE_MAX && near.distance < 0.45 * r &&
               near.second > near.distance * (1.0 + 1e-3)) {
      ASSERT_TRUE(equals(i, near.overall)) << "point " << i << ": not the nearest within half a cell";
      ++half_cell;
    } else if (near.distance >= r * (1.0 + 1e-5)) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(found[i].s[c], 0.0f) << "point " << i << " has no photon within r";
      ++dark;
    } else {
      bool matches = found[i].s[0] == 0.0f && found[i].s[1] == 0.0f && found[i].s[2] == 0.0f;
      for (size_t j = 0; j < grids.lookup.photons.size() && !matches; ++j)
        matches = glm::dot(normal_of(grids.lookup.photons[j]), n) > 0.5 &&
                  glm::length(position_of(grids.lookup.photons[j]) - x) < r * (1.0 + 1e-5) && equals(i, j);
      EXPECT_TRUE(matches) << "point " << i;
      ++loose;
    }
  }
  std::printf("%zu lookups from their own bucket, %zu from half a cell around, %zu dark, %zu loose\n", own_bucket,
              half_cell, dark, loose);
  EXPECT_GT(own_bucket, points.size() / 3);
  EXPECT_GT(half_cell, 10u);
  EXPECT_GT(dark, points.size() / 5);  // the facing no photon has, and the margins beyond the planes
}

// No photon (a scene without lights, or no surface): the map is empty and every lookup is dark.
// The grids are sorted on all cores by a two-digit radix sort; it must give what a one-pass stable counting sort
// (written here: a stable sort of the items by bucket) gives, bucket starts included, whether the bucket numbers fit
// the first digit (small maps) or need both (here up to 2^15 buckets), and whatever the hardware's thread count.
TEST(PhotonMap, GridIsAStableCountingSortByBucket) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  for (size_t count : {size_t(0), size_t(1), size_t(37), size_t(700), size_t(16000)}) {
    std::vector<PhotonHit> photons(count);
    for (size_t i = 0; i < count; ++i) {
      for (int a = 0; a < 3; ++a) photons[i].position[a] = coordinate(rng);
      photons[i].landing = int(i);  // which photon it was, to see the order within a bucket
    }
    const float radius = 0.2f;
    const PhotonGrid grid = sort_into_grid(photons, radius);
    ASSERT_EQ(grid.params.photon_count, count);
    ASSERT_EQ(grid.photons.size(), count);
    const uint32_t buckets = grid.params.bucket_count;
    auto bucket_of = [&](const PhotonHit& p) {
      int c[3];
      for (int a = 0; a < 3; ++a) c[a] = photon_cell(p.position[a], grid.params.grid_origin[a], grid.params.cell_size);
      return photon_bucket(c[0], c[1], c[2], buckets);
    };
    std::vector<PhotonHit> expected = photons;
    std::stable_sort(expected.begin(), expected.end(),
                     [&](const PhotonHit& a, const PhotonHit& b) { return bucket_of(a) < bucket_of(b); });
    std::vector<uint32_t> starts(size_t(buckets) + 1, 0);
    for (const PhotonHit& p : photons) ++starts[bucket_of(p) + 1];
    for (uint32_t b = 0; b < buckets; ++b) starts[b + 1] += starts[b];
    for (size_t i = 0; i < count; ++i)
      ASSERT_EQ(grid.photons[i].landing, expected[i].landing) << count << " photons, " << i;
    ASSERT_EQ(grid.bucket_starts, starts) << count << " photons";
  }
}

// Whether two arrays hold the same bytes (memcmp, which must not be given an empty vector's null data).
template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The device's grid sort (passes/grid_sort_pass.h) against the host's, which the test above checks against a stable
// sort: the same items in the same order and the same bucket starts, bit for bit. Random photons of several counts,
// and a crowded spot (3000 photons in one cell, whose bucket is heap-sorted) among 500 others; surface patches once.
TEST(PhotonMap, TheDeviceSortsTheGridAsTheHostDoesBitForBit) {
  GpuContext& gpu = test::gpu();
  GridSortPass sorter(gpu);
  std::mt19937 rng(15);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  auto sorted_on_device = [&](const auto& items, const PhotonMapParams& grid, auto& sorted, std::vector<uint32_t>& starts) {
    using Item = typename std::decay_t<decltype(items)>::value_type;
    const cl::Buffer given = gpu.upload(items);
    const cl::Buffer out = gpu.buffer(CL_MEM_READ_WRITE, std::max<size_t>(items.size(), 1) * sizeof(Item), "test");
    const cl::Buffer out_starts = gpu.buffer(CL_MEM_READ_WRITE, (grid.bucket_count + 1) * sizeof(cl_uint), "test");
    sorter.sort(given, sizeof(Item) / 4, uint32_t(items.size()), grid, out, out_starts);
    sorted = gpu.download<Item>(out, items.size());
    starts = gpu.download<cl_uint>(out_starts, grid.bucket_count + 1);
  };
  for (size_t count : {size_t(0), size_t(1), size_t(37), size_t(700), size_t(16000), size_t(3500)}) {
    std::vector<PhotonHit> photons(count);
    for (size_t i = 0; i < count; ++i) {
      for (int a = 0; a < 3; ++a) photons[i].position[a] = count == 3500 && i % 7 ? 0.5f : coordinate(rng);
      photons[i].landing = int(i);
      photons[i].flux[0] = coordinate(rng);
    }
    const PhotonGrid host = sort_into_grid(photons, 0.2f);
    std::vector<PhotonHit> sorted;
    std::vector<uint32_t> starts;
    const PhotonMapParams params = photon_grid_params(photons, 0.2f);
    const PhotonMapParams on_device = sorter.grid_params(gpu.upload(photons), sizeof(PhotonHit) / 4, uint32_t(count), 0.2f);
    ASSERT_EQ(std::memcmp(&params, &on_device, sizeof params), 0) << count << " photons: the grid's corner";
    sorted_on_device(photons, params, sorted, starts);
    ASSERT_EQ(starts, host.bucket_starts) << count << " photons";
    ASSERT_EQ(sorted.size(), host.photons.size());
    EXPECT_TRUE(same_bytes(sorted, host.photons)) << count;
  }
  // The grid's corner alone, over items all above zero (a group's unused items must not count), in two and three
  // rounds of groups.
  std::uniform_real_distribution<float> above_zero(2.0f, 5.0f);
  for (size_t count : {size_t(300), size_t(70001)}) {
    std::vector<PhotonHit> photons(count);
    for (PhotonHit& p : photons)
      for (int a = 0; a < 3; ++a) p.position[a] = above_zero(rng);
    const PhotonMapParams params = photon_grid_params(photons, 0.05f);
    const PhotonMapParams on_device = sorter.grid_params(gpu.upload(photons), sizeof(PhotonHit) / 4, uint32_t(count), 0.05f);
    ASSERT_EQ(std::memcmp(&params, &on_device, sizeof params), 0) << count << " photons: the grid's corner";
  }
  std::vector<SurfacePatch> patches(5000);
  for (SurfacePatch& p : patches)
    for (int a = 0; a < 3; ++a) p.position[a] = coordinate(rng), p.normal[a] = coordinate(rng);
  const PatchGrid host = sort_into_grid(patches, 0.1f);
  std::vector<SurfacePatch> sorted;
  std::vector<uint32_t> starts;
  sorted_on_device(patches, photon_grid_params(patches, 0.1f), sorted, starts);
  ASSERT_EQ(starts, host.bucket_starts);
  EXPECT_TRUE(same_bytes(sorted, host.patches));
}

// The photons a frame keeps, gathered on the device (PhotonLandingsPass) as the host does: of two rounds of landings
// the lit ones in order (a landing that left the scene, or one no flux reached, is dropped), every one's flux times
// the rounds' share, and every third taken for the lookups. Bit for bit against lit_landings and a host loop.
TEST(PhotonMap, TheDeviceKeepsTheLitLandingsAsTheHostDoes) {
  GpuContext& gpu = test::gpu();
  std::vector<PhotonHit> rounds[2];
  std::vector<PhotonHit> expected;
  for (int r = 0; r < 2; ++r) {
    rounds[r] = random_photons(3001 + 1000 * r, 30 + r).photons;
    for (size_t i = 0; i < rounds[r].size(); ++i) {
      rounds[r][i].landing = int(i);
      if (i % 5 == 1) rounds[r][i].hit = 0;
      if (i % 7 == 2) rounds[r][i].incident[0] = rounds[r][i].incident[1] = rounds[r][i].incident[2] = 0.0f;
      if (i % 7 == 3) rounds[r][i].incident[0] = rounds[r][i].incident[2] = 0.0f;  // green alone still counts
    }
    const std::vector<PhotonHit> lit = lit_landings(rounds[r]);
    expected.insert(expected.end(), lit.begin(), lit.end());
  }
  const float share = 1.0f / 3.0f;
  for (PhotonHit& p : expected)
    for (int c = 0; c < 3; ++c) p.flux[c] *= share, p.incident[c] *= share;
  PhotonLandingsPass kept(gpu);
  kept.append_lit(gpu.upload(std::vector<PhotonHit>{}), 0);  // an empty round keeps nothing
  for (const std::vector<PhotonHit>& round : rounds) kept.append_lit(gpu.upload(round), uint32_t(round.size()));
  kept.scale_flux(share);
  ASSERT_EQ(kept.kept(), expected.size());
  const std::vector<PhotonHit> got = gpu.download<PhotonHit>(kept.photons(), kept.kept());
  EXPECT_TRUE(same_bytes(got, expected));
  uint32_t taken = 0;
  const std::vector<PhotonHit> every_third = gpu.download<PhotonHit>(kept.take_every(3, taken), (expected.size() + 2) / 3);
  ASSERT_EQ(taken, (expected.size() + 2) / 3);
  for (size_t k = 0; k < taken; ++k)
    ASSERT_EQ(std::memcmp(&every_third[k], &expected[3 * k], sizeof(PhotonHit)), 0) << k;
}

// A frame's photon map, its large grids sorted on the device (sort_photon_grids), estimates what the host's grids give
// (build_photon_map), bit for bit: the same grids, read by the same kernel. With the scene's surface patches.
TEST(PhotonMap, EstimatesFromTheDeviceSortedGridsAreTheHostGridsBitForBit) {
  const std::vector<glm::vec3> triangles = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {1, 0, 0},
                                            {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 0}, {0, 1, 1}, {0, 0, 1}};
  RandomPhotons given = random_photons(20000, 17);
  for (size_t i = 0; i < given.photons.size(); ++i) given.photons[i].landing = int(1 + i / 3 % 3);
  PhotonMapGrids host = build_photon_map(given.photons, 2.0, 64, 4, triangles);
  host.shallow_landings = 2;
  PhotonMapPass from_host(test::gpu(), host);
  PhotonLandingsPass kept(test::gpu());
  kept.load(given.photons);
  PhotonMapPass from_device(test::gpu(), sort_photon_grids(test::gpu(), kept, 2.0, 64, 4, triangles, 2));
  const std::vector<cl_float4> a = test::PassProbe::photon_estimates(from_host), b = test::PassProbe::photon_estimates(from_device);
  const std::vector<cl_float4> c = test::PassProbe::shallow_photon_estimates(from_host), d = test::PassProbe::shallow_photon_estimates(from_device);
  ASSERT_EQ(a.size(), 2 * host.lookup.photons.size());
  ASSERT_EQ(b.size(), a.size());
  ASSERT_EQ(d.size(), c.size());
  EXPECT_TRUE(same_bytes(a, b));
  EXPECT_TRUE(same_bytes(c, d));
}

// The estimates' order (cell_order; the device's locality_order below) visits every photon once, a cell's photons
// together, and walks between nearby cells:
// the mean step between consecutive cells (in cells, the largest of the three axes) is at most a quarter of the bucket
// order's, which jumps about the whole grid. Photons on three planes of a cube 30 cells wide, as a scene's surfaces.
TEST(PhotonMap, CellOrderVisitsEachPhotonOnceAndWalksBetweenNearbyCells) {
  EXPECT_TRUE(cell_order(sort_into_grid(std::vector<PhotonHit>{}, 0.2f)).empty());
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> coordinate(0.0f, 6.0f);
  std::vector<PhotonHit> photons(20000);
  for (size_t i = 0; i < photons.size(); ++i) {
    for (int a = 0; a < 3; ++a) photons[i].position[a] = coordinate(rng);
    photons[i].position[i % 3] = 0.0f;
  }
  const PhotonGrid grid = sort_into_grid(photons, 0.2f);
  const std::vector<uint32_t> order = cell_order(grid);
  ASSERT_EQ(order.size(), photons.size());
  std::vector<int> seen(photons.size(), 0);
  for (uint32_t i : order) ASSERT_EQ(++seen.at(i), 1) << "photon " << i;
  auto cell_of = [&](uint32_t i) {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a)
      c[a] = photon_cell(grid.photons[i].position[a], grid.params.grid_origin[a], grid.params.cell_size);
    return c;
  };
  auto mean_step = [&](const std::vector<uint32_t>& walk, size_t* runs) {
    double steps = 0.0;
    *runs = 1;
    for (size_t k = 1; k < walk.size(); ++k) {
      std::array<int, 3> a = cell_of(walk[k - 1]), b = cell_of(walk[k]);
      if (a == b) continue;
      ++*runs;
      steps += std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
    }
    return steps / double(*runs - 1);
  };
  std::set<std::array<int, 3>> cells;
  for (uint32_t i = 0; i < photons.size(); ++i) cells.insert(cell_of(i));
  std::vector<uint32_t> bucket_order(photons.size());
  for (uint32_t i = 0; i < photons.size(); ++i) bucket_order[i] = i;
  size_t runs = 0, bucket_runs = 0;
  const double step = mean_step(order, &runs), bucket_step = mean_step(bucket_order, &bucket_runs);
  EXPECT_EQ(runs, cells.size());  // each cell's photons in one run
  EXPECT_LT(step, 0.25 * bucket_step) << "cell order " << step << ", bucket order " << bucket_step;

  // The device's order (GridSortPass::locality_order, what frames use): every photon once and as local, here at
  // whole cells (2 x 20,000 codes allow 32 a side, and the photons span about 30 cells) and, with a tenth of the
  // photons, at cells grouped 4 x 4 x 4 (2 x 2,000 codes allow 8 a side).
  GpuContext& gpu = test::gpu();
  GridSortPass sorter(gpu);
  for (const size_t count : {photons.size(), photons.size() / 10}) {
    const std::vector<PhotonHit> some(grid.photons.begin(), grid.photons.begin() + std::ptrdiff_t(count));
    const cl::Buffer on_device = gpu.upload(some), placed = gpu.buffer(CL_MEM_READ_WRITE, count * 4, "test");
    sorter.locality_order(on_device, sizeof(PhotonHit) / 4, uint32_t(count), grid.params, placed);
    const std::vector<uint32_t> device_order = gpu.download<uint32_t>(placed, count);
    std::vector<int> visits(count, 0);
    for (uint32_t i : device_order) ASSERT_EQ(++visits.at(i), 1) << "photon " << i << " of " << count;
    std::vector<uint32_t> given(count);
    for (uint32_t i = 0; i < count; ++i) given[i] = i;
    size_t device_runs = 0, given_runs = 0;
    const double device_step = mean_step(device_order, &device_runs), given_step = mean_step(given, &given_runs);
    EXPECT_LT(device_step, 0.25 * given_step) << count << " photons: device order " << device_step << ", bucket order "
                                             << given_step;
  }
}

// The surface patches cut on the device (SurfacePatchPass, where it has doubles) are the host's, byte for byte:
// random triangles from tiny to large, and one huge (past the 256 x 256 cap), some degenerate (a repeated corner, a line, a NaN), at
// two patch areas; none for a zero or infinite area. Planted once: the centroids' thirds in float failed the bytes.
TEST(PhotonMap, TheDeviceCutsTheHostsSurfacePatches) {
  GpuContext& gpu = test::gpu();
  if (!SurfacePatchPass::available(gpu)) GTEST_SKIP() << "the device has no doubles: the host cuts the patches";
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-4.0f, 0.5f);
  std::vector<glm::vec3> corners;
  for (int t = 0; t < 1500; ++t) {
    const glm::vec3 a(3.0f * u(rng), 3.0f * u(rng), 3.0f * u(rng));
    const float size = std::pow(10.0f, scale(rng));
    glm::vec3 b = a + size * glm::vec3(u(rng), u(rng), u(rng)), c = a + size * glm::vec3(u(rng), u(rng), u(rng));
    if (t % 101 == 1) b = a;                // a repeated corner
    if (t % 101 == 2) c = a + 2.0f * (b - a);  // a line
    if (t % 101 == 3) c.x = std::nanf("");
    corners.insert(corners.end(), {a, b, c});
  }
  SurfacePatchPass cutter(gpu);
  for (const float area : {1e-3f, 4e-2f}) {
    const std::vector<SurfacePatch> host = surface_patches(corners, area);
    uint32_t count = 0;
    const cl::Buffer patches = cutter.cut(corners, area, count);
    ASSERT_EQ(count, host.size()) << "area " << area;
    EXPECT_GT(host.size(), 4 * corners.size() / 3) << "most triangles cut more than once";
    EXPECT_TRUE(same_bytes(gpu.download<SurfacePatch>(patches, count), host)) << "area " << area;
  }
  const std::vector<glm::vec3> huge = {{0, 0, 0}, {1e3f, 0, 0}, {0, 1e3f, 0}};
  uint32_t count = 0;
  cutter.cut(huge, 1e-2f, count);
  EXPECT_EQ(count, 2u * 256u * 256u) << "the cap";
  for (const float none : {0.0f, INFINITY}) {
    cutter.cut(corners, none, count);
    EXPECT_EQ(count, 0u);
  }
}

TEST(PhotonMap, AnEmptyMapIsDark) {
  PhotonMapGrids grids = build_photon_map({}, 1.0, 32, 4);
  PhotonMapPass pass(test::gpu(), grids);
  std::vector<cl_float4> found =
      test::photon_radiance_at(test::gpu(), pass, {{{0.0f, 0.0f, 0.0f, 0.0f}}}, {{{0.0f, 1.0f, 0.0f, 0.0f}}});
  EXPECT_EQ(found[0].s[0], 0.0f);
  PhotonMapGrids no_area = build_photon_map(random_photons(30, 1).photons, 0.0, 32, 4);
  EXPECT_EQ(no_area.lookup.params.photon_count, 0u);
}

// --bounces 0: the fewest bounces that leave out at most 5% of the indirect light of a geometric series.
TEST(BounceChoice, FewestBouncesThatLeaveOutAtMostFivePercent) {
  EXPECT_EQ(bounces_for(0.0, 8), 1u);
  EXPECT_EQ(bounces_for(0.05, 8), 1u);
  EXPECT_EQ(bounces_for(0.2, 8), 2u);   // 0.2 left out by one, 0.04 by two
  EXPECT_EQ(bounces_for(0.5, 8), 5u);   // 0.0625 by four, 0.031 by five
  EXPECT_EQ(bounces_for(0.99, 8), 8u);  // the maximum
  EXPECT_EQ(bounces_for(0.99, 3), 3u);
}

// The scene's measure: in the closed cube of albedo 0.5 each reflection keeps exactly half (every photon lands again),
// so five bounces, for a render and a path-traced reference alike; a floor alone under a light keeps nothing (what it
// reflects leaves), so one. Auto picks photons for the cache and path under a sky.
TEST(BounceChoice, ClosedCubeKeepsHalfAndAnOpenFloorNothing) {
  Scene cube = lit_closed_cube();
  Bvh8 bvh = build_bvh8(cube.positions);
  DeviceScene device(test::gpu(), cube, bvh);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.bounces = 0;
  BounceChoice choice = choose_bounces(test::gpu(), cube, device, settings);
  EXPECT_NEAR(choice.kept_per_bounce, 0.5, 1e-4);
  EXPECT_EQ(choice.bounces, 5u);
  EXPECT_EQ(choice.method, BounceMethod::photons);
  EXPECT_TRUE(choice.bounces_chosen);
  settings.gi = GiMethod::path;  // a reference chooses what a render does
  EXPECT_EQ(choose_bounces(test::gpu(), cube, device, settings).bounces, 5u);
  settings.gi = GiMethod::splat;
  settings.bounces = 2;
  EXPECT_FALSE(choose_bounces(test::gpu(), cube, device, settings).bounces_chosen);

  Scene floor;
  floor.source = "floor";
  floor.materials.push_back({"white", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), -1, glm::vec3(0.0f), false});
  floor.add_quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, 0);
  floor.lights.push_back({"point", LightType::point, {0.0f, 0.5f, 0.0f}, {0, 0, -1}, glm::vec3(1.0f)});
  Bvh8 floor_bvh = build_bvh8(floor.positions);
  DeviceScene floor_device(test::gpu(), floor, floor_bvh);
  settings.bounces = 0;
  settings.bounce_method = BounceMethod::automatic;
  BounceChoice open = choose_bounces(test::gpu(), floor, floor_device, settings);
  EXPECT_EQ(open.kept_per_bounce, 0.0);
  EXPECT_EQ(open.bounces, 1u);
  EnvironmentSettings sky;
  sky.sky = glm::vec3(1.0f);
  floor.environment = make_environment(sky);
  EXPECT_EQ(choose_bounces(test::gpu(), floor, floor_device, settings).method, BounceMethod::path);
}

// A scene lit by a sky alone: the probe shoots the sky's smooth part too (a direction uniform over the sphere, through
// a disc beyond the scene). A floor under the sky keeps nothing, as under a light. A well (1 x 1, 4 deep, open at the
// top, albedo 0.5, in a black shell so that only its inside is lit) keeps a good part of each reflection, less than
// its albedo (some leaves through the opening), so it takes more than one bounce; before the sky was a source it
// measured 0 and took one.
TEST(BounceChoice, ASkyAloneIsMeasuredToo) {
  EnvironmentSettings sky_settings;
  sky_settings.sky = glm::vec3(1.0f);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.bounces = 0;

  Scene floor;
  floor.source = "floor under a sky";
  floor.materials.push_back({"white", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), -1, glm::vec3(0.0f), false});
  floor.add_quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, 0);
  floor.environment = make_environment(sky_settings);
  Bvh8 floor_bvh = build_bvh8(floor.positions);
  DeviceScene floor_device(test::gpu(), floor, floor_bvh);
  EXPECT_EQ(choose_bounces(test::gpu(), floor, floor_device, settings).bounces, 1u);

  Scene well;
  well.source = "well under a sky";
  well.materials.push_back({"grey", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  const float h = 4.0f;
  well.add_quad({-0.5f, 0, -0.5f}, {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}, 0);
  well.add_quad({-0.5f, 0, -0.5f}, {-0.5f, h, -0.5f}, {-0.5f, h, 0.5f}, {-0.5f, 0, 0.5f}, 0);
  well.add_quad({0.5f, 0, -0.5f}, {0.5f, 0, 0.5f}, {0.5f, h, 0.5f}, {0.5f, h, -0.5f}, 0);
  well.add_quad({-0.5f, 0, -0.5f}, {0.5f, 0, -0.5f}, {0.5f, h, -0.5f}, {-0.5f, h, -0.5f}, 0);
  well.add_quad({-0.5f, 0, 0.5f}, {-0.5f, h, 0.5f}, {0.5f, h, 0.5f}, {0.5f, 0, 0.5f}, 0);
  // The black shell: walls 0.05 outside the well's, a bottom below it and a rim around the opening.
  well.materials.push_back({"black", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), -1, glm::vec3(0.0f), false});
  const float o = 0.55f, i = 0.5f;
  well.add_quad({-o, -0.1f, -o}, {-o, -0.1f, o}, {o, -0.1f, o}, {o, -0.1f, -o}, 1);
  well.add_quad({-o, -0.1f, -o}, {-o, h, -o}, {-o, h, o}, {-o, -0.1f, o}, 1);
  well.add_quad({o, -0.1f, -o}, {o, -0.1f, o}, {o, h, o}, {o, h, -o}, 1);
  well.add_quad({-o, -0.1f, -o}, {o, -0.1f, -o}, {o, h, -o}, {-o, h, -o}, 1);
  well.add_quad({-o, -0.1f, o}, {-o, h, o}, {o, h, o}, {o, -0.1f, o}, 1);
  well.add_quad({-o, h, -o}, {-o, h, o}, {-i, h, o}, {-i, h, -o}, 1);
  well.add_quad({i, h, -o}, {i, h, o}, {o, h, o}, {o, h, -o}, 1);
  well.add_quad({-i, h, -o}, {-i, h, -i}, {i, h, -i}, {i, h, -o}, 1);
  well.add_quad({-i, h, i}, {-i, h, o}, {i, h, o}, {i, h, i}, 1);
  well.environment = make_environment(sky_settings);
  Bvh8 well_bvh = build_bvh8(well.positions);
  DeviceScene well_device(test::gpu(), well, well_bvh);
  const BounceChoice choice = choose_bounces(test::gpu(), well, well_device, settings);
  std::printf("well under a sky: each reflection keeps %.3f, %u bounces\n", choice.kept_per_bounce, choice.bounces);
  EXPECT_GT(choice.kept_per_bounce, 0.2);
  EXPECT_LT(choice.kept_per_bounce, 0.5);
  EXPECT_GE(choice.bounces, 2u);
  EXPECT_EQ(choice.method, BounceMethod::path);
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// Issue 41 item 4: in a room lit through a gap (tests/gap_room_scene.h) the near side holds few photons. The render
// defaults (8 bounces, photon map) must agree with the same records' later bounces by path continuation, which has no
// density estimate to bias it. Two seeds each at 96 x 72; their means' spread over seeds is 0.2% (0.3% for path
// continuation) at 320 x 240 (benchmarks/gap_room, 4 seeds), a few times that here: 2% is the tolerance. Before issue
// 41 (every lookup read the map, black where it found no photon: --photon-min-support 0) the defaults read 4% dark.
TEST(PhotonMap, RoomLitThroughAGapMatchesPathContinuation) {
  const Scene room = test::gap_lit_room();
  Renderer renderer(test::gpu(), room);
  RenderSettings defaults;
  defaults.width = 96;
  defaults.height = 72;
  const FramePlan plan = renderer.plan(defaults);
  ASSERT_EQ(plan.settings.bounce_method, BounceMethod::photons);
  ASSERT_GE(plan.settings.bounces, 4u);
  RenderSettings path = defaults;
  path.bounces = plan.settings.bounces;
  path.bounce_method = BounceMethod::path;
  auto mean_over_seeds = [&](RenderSettings s) {
    double sum = 0.0;
    for (unsigned seed : {1u, 2u}) {
      s.seed = seed;
      const RenderedImage image = renderer.render(s);
      for (float v : image.color) sum += v;
    }
    return sum;
  };
  const double photons = mean_over_seeds(defaults), continued = mean_over_seeds(path);
  std::printf("defaults over path continuation: %.4f\n", photons / continued);
  EXPECT_NEAR(photons / continued, 1.0, 0.02);
}

}  // namespace
}  // namespace rcsplat
