// The light guide (issue 10): the photons carry the lights' reflected power, and clustering keeps a small bright patch
// apart from an evenly lit wall.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "bvh/bvh8.h"
#include "cache/light_guide.h"
#include "cl/device_scene.h"
#include "passes/guide_cluster_pass.h"
#include "passes/light_guide_pass.h"
#include "corridor_scene.h"
#include "scene/cornell_box.h"
#include "scene/scene_frame.h"
#include "closed_cube.h"
#include "test_support.h"

namespace rcsplat {
namespace {

constexpr double kPi = std::numbers::pi;

using test::closed_cube;

double reflected_flux(const std::vector<PhotonHit>& photons, size_t* hits = nullptr) {
  double sum = 0.0;
  size_t n = 0;
  for (const PhotonHit& p : photons) {
    n += p.hit != 0;
    sum += 0.2126 * p.flux[0] + 0.7152 * p.flux[1] + 0.0722 * p.flux[2];
  }
  if (hits) *hits = n;
  return sum;
}

std::vector<PhotonHit> shoot(const Scene& scene, unsigned photons) {
  Bvh8 bvh = build_bvh8(scene.positions);
  DeviceScene device(test::gpu(), scene, bvh);
  return LightGuidePass(test::gpu(), device).shoot(photons, 3);
}

// In a closed cube every photon lands, and what the walls reflect is albedo times what the lights emit: a point light
// 4 pi I, an emissive triangle pi L A, a spot I times the integral of glTF's smooth falloff over its cone (computed
// here by quadrature). Photons of one light carry equal power, so one light alone sums exactly; with several, the
// choice of light is random and the sum is right to within its noise (about 1 / sqrt(photons)).
TEST(LightGuide, PhotonsCarryTheLightsReflectedPower) {
  const unsigned photons = 1u << 16;
  Scene point = closed_cube();
  point.lights.push_back({"point", LightType::point, {0.1f, 0.2f, -0.1f}, {0, 0, -1}, glm::vec3(3.0f)});
  size_t hits = 0;
  EXPECT_NEAR(reflected_flux(shoot(point, photons), &hits), 0.5 * 4.0 * kPi * 3.0, 1e-4 * 0.5 * 4.0 * kPi * 3.0);
  EXPECT_EQ(hits, photons);

  Scene emitter = closed_cube();
  // The lamp reflects like the walls: photons from another light that land on it count the same.
  emitter.materials.push_back({"lamp", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(5.0f), false});
  emitter.add_triangle({-0.2f, 0.49f, -0.2f}, {0.2f, 0.49f, 0.2f}, {-0.2f, 0.49f, 0.2f}, 1);  // faces down
  const double lamp_area = 0.5 * 0.4 * 0.4;
  EXPECT_NEAR(reflected_flux(shoot(emitter, photons)), 0.5 * kPi * 5.0 * lamp_area, 1e-4 * 0.5 * kPi * 5.0 * lamp_area);

  Scene spot = closed_cube();
  SceneLight s{"spot", LightType::spot, {0.0f, 0.3f, 0.0f}, {0.0f, -1.0f, 0.0f}, glm::vec3(7.0f)};
  s.inner_cone = 0.2f;
  s.outer_cone = 0.6f;
  spot.lights.push_back(s);
  const double cos_inner = std::cos(0.2), cos_outer = std::cos(0.6), rows = 100000;
  double integral = 0.0;  // of saturate((cos - cos_outer) / (cos_inner - cos_outer))^2 over the cone's solid angle
  for (int i = 0; i < int(rows); ++i) {
    double c = 1.0 - (i + 0.5) / rows * (1.0 - cos_outer);
    double a = std::clamp((c - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
    integral += a * a * 2.0 * kPi * (1.0 - cos_outer) / rows;
  }
  const double spot_power = 0.5 * 7.0 * integral;
  EXPECT_NEAR(reflected_flux(shoot(spot, photons)), spot_power, 0.02 * spot_power);

  Scene both = emitter;
  both.lights = point.lights;
  const double expected = 0.5 * (4.0 * kPi * 3.0 + kPi * 5.0 * lamp_area);
  EXPECT_NEAR(reflected_flux(shoot(both, photons)), expected, 0.02 * expected);
}

// A directional light's photons cross the unit disc facing it: on a floor wider than that disc, the floor reflects
// albedo times pi E.
TEST(LightGuide, DirectionalPhotonsCrossTheUnitDisc) {
  Scene floor;
  floor.source = "floor";
  floor.materials.push_back({"grey", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  floor.add_quad({-1.5f, 0, -1.5f}, {-1.5f, 0, 1.5f}, {1.5f, 0, 1.5f}, {1.5f, 0, -1.5f}, 0);
  floor.lights.push_back({"sun", LightType::directional, {0, 0, 0}, {0.0f, -1.0f, 0.0f}, glm::vec3(2.0f)});
  size_t hits = 0;
  EXPECT_NEAR(reflected_flux(shoot(floor, 1u << 14), &hits), 0.5 * kPi * 2.0, 1e-4 * 0.5 * kPi * 2.0);
  EXPECT_EQ(hits, 1u << 14);
}

// The environment's peak (a sun) sends its photons through the unit disc facing each sampled direction, so a floor
// wider than every such disc's shadow reflects albedo times pi times the peak's integral of radiance over solid
// angle (its peak_power, for a grey map). Each photon carries the same power, so the sum is exact to rounding.
TEST(LightGuide, EnvironmentPeakPhotonsCrossTheUnitDisc) {
  Scene floor;
  floor.source = "floor";
  floor.materials.push_back({"grey", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), -1, glm::vec3(0.0f), false});
  floor.add_quad({-2.5f, 0, -2.5f}, {-2.5f, 0, 2.5f}, {2.5f, 0, 2.5f}, {2.5f, 0, -2.5f}, 0);
  // A grey 16 x 8 map, its sun two texels at 22 to 45 degrees from the zenith.
  floor.environment.width = 16;
  floor.environment.height = 8;
  floor.environment.source = "grey sun";
  for (int t = 0; t < 16 * 8; ++t)
    floor.environment.radiance.push_back(glm::vec3(t == 16 + 5 || t == 16 + 6 ? 50.0f : 0.2f));
  const double peak_power = pack_environment(floor.environment).peak_power;
  ASSERT_GT(peak_power, 0.0);
  size_t hits = 0;
  EXPECT_NEAR(reflected_flux(shoot(floor, 1u << 14), &hits), 0.5 * kPi * peak_power, 1e-4 * 0.5 * kPi * peak_power);
  EXPECT_EQ(hits, 1u << 14);
}

// An evenly lit wall and, on it, a small patch a hundred times brighter per photon: the patch is the brightest
// cluster, tight around its photons; the wall is one large cluster.
TEST(LightGuide, SmallBrightPatchIsAClusterOfItsOwn) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<PhotonHit> photons;
  auto add = [&](float x, float y, float flux) {
    PhotonHit p{};
    p.position[0] = x;
    p.position[1] = y;
    p.position[2] = -0.5f;
    p.normal[2] = 1.0f;  // the wall z = -0.5 faces +z
    p.hit = 1;
    p.flux[0] = p.flux[1] = p.flux[2] = flux;
    photons.push_back(p);
  };
  for (int i = 0; i < 20000; ++i) add(0.8f * unit(rng), 0.8f * unit(rng), 1.0f);
  for (int i = 0; i < 2000; ++i) {
    float r = 0.01f * std::sqrt(0.5f * (unit(rng) + 1.0f)), phi = float(kPi) * unit(rng);
    add(0.3f + r * std::cos(phi), -0.2f + r * std::sin(phi), 100.0f);
  }
  std::vector<GuideCluster> clusters = cluster_photons(photons, GUIDE_MAX_CLUSTERS);
  ASSERT_GE(clusters.size(), 2u);
  EXPECT_NEAR(clusters[0].centre[0], 0.3f, 0.003f);
  EXPECT_NEAR(clusters[0].centre[1], -0.2f, 0.003f);
  EXPECT_LT(clusters[0].radius, 0.02f);
  // The patch's bins also hold the wall photons that share their cells (about 30 a cell).
  EXPECT_NEAR(clusters[0].flux[0], 2000.0f * 100.0f + 60.0f, 60.0f);
  EXPECT_NEAR(clusters[0].normal[2], 1.0f, 1e-6f);
  EXPECT_GT(clusters[1].radius, 1.0f) << "the evenly lit wall is one region";
  EXPECT_EQ(clusters.size(), 2u);
}

// The clusters made on the device (passes/guide_cluster_pass.h) are the host's, bit for bit: from photons shot in the
// corridor with its bright patch (the guide the frames use: 2^14 photons), in the Cornell box, and from made-up
// photons that try the edges: cells past the grid on every side, every facing, photons that left the scene or carry no
// light or a NaN, neighbouring bins of fluxes near the join's ratio of 8, and more regions than clusters kept.
TEST(LightGuide, TheDeviceClustersAsTheHostDoesBitForBit) {
  GpuContext& gpu = test::gpu();
  if (!GuideClusterPass::available(gpu)) GTEST_SKIP() << "the device has no doubles (cl_khr_fp64)";
  GuideClusterPass pass(gpu);
  auto expect_same = [&](const std::vector<PhotonHit>& photons, unsigned max_clusters, const char* what) {
    const std::vector<GuideCluster> host = cluster_photons(photons, max_clusters);
    const std::vector<GuideCluster> device =
        pass.cluster(gpu.upload(photons), uint32_t(photons.size()), max_clusters);
    ASSERT_EQ(device.size(), host.size()) << what;
    for (size_t c = 0; c < host.size(); ++c)
      EXPECT_EQ(std::memcmp(&device[c], &host[c], sizeof(GuideCluster)), 0) << what << ": cluster " << c;
    std::printf("%s: %zu photons, %zu clusters, %u rounds of joining\n", what, photons.size(), host.size(),
                pass.rounds());
  };
  const Scene corridor = test::bright_patch_corridor();
  for (const auto& [what, scene] : {std::pair{"corridor", corridor}, std::pair{"Cornell box", make_cornell_box()}}) {
    const Scene fitted = SceneFrame::fitted(scene).device_scene(scene);
    Bvh8 bvh = build_bvh8(fitted.positions);
    DeviceScene device(gpu, fitted, bvh);
    expect_same(LightGuidePass(gpu, device).shoot(1u << 14, 5), GUIDE_MAX_CLUSTERS, what);
  }
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> span(-1.15f, 1.15f), unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> pick(0, 15);
  std::vector<PhotonHit> made_up;
  for (int i = 0; i < 30000; ++i) {
    PhotonHit p{};
    for (int a = 0; a < 3; ++a) {
      p.position[a] = span(rng);
      p.normal[a] = unit(rng);
    }
    p.hit = pick(rng) != 0;
    // Fluxes in steps of a factor near the join's ratio across x: neighbouring bins join or not by a hair.
    const float flux = std::pow(7.9f, std::floor((p.position[0] + 1.2f) * 8.0f) / 4.0f) * (1.0f + 0.1f * unit(rng));
    for (float& f : p.flux) f = flux * (0.5f + 0.5f * std::abs(unit(rng)));
    const int kind = pick(rng);
    if (kind == 1) p.flux[0] = p.flux[1] = p.flux[2] = 0.0f;
    if (kind == 2) p.flux[1] = std::nanf("");
    made_up.push_back(p);
  }
  expect_same(made_up, GUIDE_MAX_CLUSTERS, "made-up photons");
  expect_same(made_up, 5, "made-up photons, 5 clusters");
}

}  // namespace
}  // namespace rcsplat
