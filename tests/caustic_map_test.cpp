// The caustic map (issue 41 item 1): its density estimate against a double-precision sum, its photons, and the split
// it makes with the records (light -> glossy -> rough counted once) against the path tracer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>

#include "cl/device_scene.h"
#include "image/error_metrics.h"
#include "kernels/photon_grid.h"
#include "passes/caustic_map_pass.h"
#include "render/renderer.h"
#include "caustic_room_scene.h"
#include "pass_probe.h"
#include "test_support.h"

namespace rcsplat {
namespace {

PhotonHit caustic_photon(glm::vec3 position, glm::vec3 normal, glm::vec3 incident) {
  PhotonHit p{};
  p.hit = 1;
  p.landing = 1;
  for (int a = 0; a < 3; ++a) {
    p.position[a] = position[a];
    p.normal[a] = normal[a];
    p.incident[a] = incident[a];
    p.flux[a] = 0.5f * incident[a];
  }
  return p;
}

// Random photons on a floor (y = 0, facing up), a wall (z = 0, facing +z) and a shelf a little above the floor
// (y = 0.4 r, facing up: inside the disc's half-thickness of 0.2 r only for points near it), read at random points of
// the floor and the wall. The kernel's sum is float; the reference sums in double: 1e-4 relative.
TEST(CausticMap, IrradianceMatchesADoublePrecisionSumOverTheDisc) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float radius = 0.05f;
  std::vector<PhotonHit> photons;
  for (int i = 0; i < 40000; ++i) {
    glm::vec3 flux(u(rng), u(rng), u(rng));
    flux *= 1e-4f;
    switch (i % 3) {
      case 0: photons.push_back(caustic_photon({u(rng), 0.0f, u(rng)}, {0, 1, 0}, flux)); break;
      case 1: photons.push_back(caustic_photon({u(rng), u(rng), 0.0f}, {0, 0, 1}, flux)); break;
      default: photons.push_back(caustic_photon({u(rng), 0.4f * radius, u(rng)}, {0, 1, 0}, flux)); break;
    }
  }
  CausticMapPass map(test::gpu(), photons, radius);
  ASSERT_EQ(map.params().photon_count, photons.size());
  std::vector<cl_float4> points, normals;
  for (int i = 0; i < 2000; ++i) {
    const bool floor = i % 2 == 0;
    points.push_back(floor ? cl_float4{{u(rng), 0.0f, u(rng), 0.0f}} : cl_float4{{u(rng), u(rng), 0.0f, 0.0f}});
    normals.push_back(floor ? cl_float4{{0, 1, 0, 0}} : cl_float4{{0, 0, 1, 0}});
  }
  const std::vector<cl_float4> got = test::caustic_irradiance_at(test::gpu(), map, points, normals);
  const double r2 = double(radius) * radius, half = PHOTON_DISC_HALF_THICKNESS * double(radius);
  size_t lit = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    glm::dvec3 x(points[i].s[0], points[i].s[1], points[i].s[2]), n(normals[i].s[0], normals[i].s[1], normals[i].s[2]);
    glm::dvec3 sum(0.0);
    for (const PhotonHit& p : photons) {
      glm::dvec3 d = glm::dvec3(p.position[0], p.position[1], p.position[2]) - x;
      glm::dvec3 m(p.normal[0], p.normal[1], p.normal[2]);
      if (glm::dot(d, d) < r2 && std::abs(glm::dot(d, n)) < half && glm::dot(m, n) > PHOTON_MIN_NORMAL_COSINE)
        sum += glm::dvec3(p.incident[0], p.incident[1], p.incident[2]);
    }
    sum /= std::numbers::pi * r2;
    lit += sum.x > 0.0;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[i].s[c], sum[c], 1e-4 * sum[c] + 1e-9) << "point " << i;
  }
  EXPECT_GT(lit, points.size() * 9 / 10);
}

// The records the glossy pass reads carry the caustic irradiance at their points (CausticMapPass::lit_records, on the
// device): each record's own irradiance plus the map's lookup at its position and normal, as the host adds them,
// bit for bit; the rest of each record unchanged; an empty map gives the records themselves.
TEST(CausticMap, LitRecordsAddTheMapsIrradianceAtEachRecord) {
  std::mt19937 rng(47);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float radius = 0.05f;
  std::vector<PhotonHit> photons;
  for (int i = 0; i < 20000; ++i)
    photons.push_back(caustic_photon({u(rng), 0.0f, u(rng)}, {0, 1, 0}, 1e-4f * glm::vec3(u(rng), u(rng), u(rng))));
  CausticMapPass map(test::gpu(), photons, radius);
  std::vector<CacheRecord> records(600);
  std::vector<cl_float4> points, normals;
  for (CacheRecord& r : records) {
    r = CacheRecord{};
    const bool floor = points.size() % 3 != 0;  // a third on a wall the floor's photons do not face
    const glm::vec3 p = floor ? glm::vec3(u(rng), 0.0f, u(rng)) : glm::vec3(u(rng), u(rng), 0.0f);
    const glm::vec3 n = floor ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    for (int a = 0; a < 3; ++a) {
      r.position[a] = p[a];
      r.normal[a] = n[a];
      r.irradiance[a] = u(rng);
    }
    r.radius = 0.1f * u(rng);
    r.pixel = int(points.size());
    points.push_back({{p.x, p.y, p.z, 0.0f}});
    normals.push_back({{n.x, n.y, n.z, 0.0f}});
  }
  const std::vector<cl_float4> caustic = test::caustic_irradiance_at(test::gpu(), map, points, normals);
  const cl::Buffer on_device = test::gpu().upload(records);
  const cl::Buffer& lit_buffer = map.lit_records(on_device, uint32_t(records.size()));
  const std::vector<CacheRecord> lit = test::gpu().download<CacheRecord>(lit_buffer, records.size());
  size_t brightened = 0;
  for (size_t i = 0; i < records.size(); ++i) {
    CacheRecord expected = records[i];
    for (int c = 0; c < 3; ++c) expected.irradiance[c] += caustic[i].s[c];
    brightened += caustic[i].s[0] > 0.0f;
    EXPECT_EQ(std::memcmp(&lit[i], &expected, sizeof(CacheRecord)), 0) << "record " << i;
  }
  EXPECT_GT(brightened, records.size() / 2);
  EXPECT_LT(brightened, records.size());
  CausticMapPass empty(test::gpu(), {}, radius);
  EXPECT_EQ(&empty.lit_records(on_device, uint32_t(records.size())), &on_device);
}

// Mean of an RGB layer.
double mean_of(const std::vector<float>& rgb) {
  double sum = 0.0;
  for (float v : rgb) sum += v;
  return sum / double(rgb.size());
}

// 256 stratified paths a pixel of the frame `cache` asks for, at the bounces it settles on: the indirect layer's mean
// and that mean's variance (from the reference's per-pixel variance).
struct PathReference {
  RenderedImage image;
  double mean = 0, variance_of_mean = 0;
};
PathReference path_reference(Renderer& renderer, const RenderSettings& cache) {
  RenderSettings path = cache;
  path.bounces = renderer.plan(cache).settings.bounces;
  path.gi = GiMethod::path;
  path.path.samples = 256;
  path.path.stratified = true;
  PathReference r{renderer.render(path)};
  r.mean = mean_of(r.image.indirect);
  for (float v : r.image.indirect_variance) r.variance_of_mean += v;
  r.variance_of_mean /= double(r.image.indirect_variance.size()) * double(r.image.indirect_variance.size());
  return r;
}

// The split against the path tracer, in a room whose far wall and ceiling a glossy floor lights with the lamp's
// mirror image (tests/caustic_room_scene.h): the cache's indirect light (records without the caustic paths, plus the
// caustic map at the pixels) must agree with path tracing, which counts the caustic through each path's light sample
// at the floor. A path lost (the map not read) or counted twice (the records keeping it too) moves the mean by the
// caustic's share of the indirect light, which the test prints (about 20%). Tolerance: four standard deviations of the
// reference's mean (from its per-pixel variance) plus 3% for the cache's own error at 96 x 72 (interpolation and the
// map's blur, seeds averaged). The glossy floor's samples continue their paths (--glossy-paths), as the path tracer
// does: reading the records where they land (the render defaults) adds a bounce the reference leaves out
// (docs/ALGORITHM.md section 8; about +1.5% here when it was printed), which is item 2's trade, not this split's, so
// the test no longer spends two renders on it.
TEST(CausticMap, GlossyFloorRoomMatchesThePathTracer) {
  const Scene room = test::caustic_room();
  Renderer renderer(test::gpu(), room);
  RenderSettings cache;
  cache.width = 96;
  cache.height = 72;
  cache.glossy_reads_records = false;
  const PathReference path = path_reference(renderer, cache);
  const double reference_mean = path.mean, variance_of_mean = path.variance_of_mean;
  auto cache_mean = [&](unsigned caustic_photons) {
    double sum = 0.0;
    for (unsigned seed : {1u, 2u}) {
      RenderSettings s = cache;
      s.seed = seed;
      s.caustic_photons = caustic_photons;
      const RenderedImage image = renderer.render(s);
      if (caustic_photons) EXPECT_GT(image.stats.caustics.photons, 10000u);
      sum += mean_of(image.indirect);
    }
    return sum / 2.0;
  };
  const double with_map = cache_mean(cache.caustic_photons), without_map = cache_mean(0);
  const double tolerance = 4.0 * std::sqrt(variance_of_mean) / reference_mean + 0.03;
  std::printf("indirect over the path tracer's: caustic map %.4f, records alone %.4f (tolerance %.4f)\n",
              with_map / reference_mean, without_map / reference_mean, tolerance);
  EXPECT_NEAR(with_map / reference_mean, 1.0, tolerance);
  EXPECT_NEAR(without_map / reference_mean, 1.0, tolerance);
}

// Pixels of a layer (three floats a pixel) whose luminance exceeds ten times the median of their 5 x 5 neighbourhood
// plus `floor`: fireflies, a sample worth hundreds of the pixel's others.
int fireflies(const std::vector<float>& rgb, int width, int height, double floor) {
  std::vector<double> lum(size_t(width) * height);
  for (size_t i = 0; i < lum.size(); ++i) lum[i] = 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
  int count = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::vector<double> near;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          near.push_back(lum[size_t(std::clamp(y + dy, 0, height - 1)) * width + std::clamp(x + dx, 0, width - 1)]);
      std::nth_element(near.begin(), near.begin() + 12, near.end());
      if (lum[size_t(y) * width + x] > 10.0 * near[12] + floor) ++count;
    }
  return count;
}

// Issue 59 item 1 (textured Sibenik's floor): a sharp metal floor (roughness 0.06) seen from above, the room's walls
// off screen, so no record reaches them. A glossy sample's path that went floor -> wall -> floor used to find the
// lamp's highlight in the floor through a random direction from the wall, one path in thousands: single pixels
// hundreds of times their neighbours. The path now reads the caustic map at the wall instead (kernels/glossy.cl
// glossy_path_step). Checked: no such pixel in two seeds, and the indirect mean still the path tracer's (which traces
// those paths, unbiased, noisy) within four of its standard errors plus 3%.
TEST(CausticMap, GlossyPathsPastWallsNoRecordReachesReadTheMapWithoutFireflies) {
  Scene room = test::caustic_room(0.06f);
  room.cameras.clear();
  test::add_camera(room, {0.0f, 2.2f, -1.0f}, {0.0f, 0.0f, -2.2f}, 0.45f);
  Renderer renderer(test::gpu(), room);
  RenderSettings cache;
  cache.width = 64;
  cache.height = 48;
  const PathReference path = path_reference(renderer, cache);
  const RenderedImage& reference = path.image;
  const double reference_mean = path.mean, variance_of_mean = path.variance_of_mean;
  double cache_mean = 0.0;
  for (unsigned seed : {1u, 2u}) {
    RenderSettings s = cache;
    s.seed = seed;
    const RenderedImage image = renderer.render(s);
    EXPECT_GT(image.stats.glossy.rays, 0u);
    EXPECT_GT(image.stats.caustics.photons, 1000u);
    const int bright = fireflies(image.indirect, image.width, image.height, 0.1 * reference_mean);
    std::printf("seed %u: %d fireflies, indirect mean %.4f over the path tracer's\n", seed, bright,
                mean_of(image.indirect) / reference_mean);
    EXPECT_EQ(bright, 0) << "seed " << seed;
    cache_mean += mean_of(image.indirect) / 2.0;
  }
  const double tolerance = 4.0 * std::sqrt(variance_of_mean) / reference_mean + 0.03;
  std::printf("indirect over the path tracer's %.4f (tolerance %.4f); the path tracer's own fireflies: %d\n",
              cache_mean / reference_mean, tolerance,
              fireflies(reference.indirect, reference.width, reference.height, 0.1 * reference_mean));
  EXPECT_NEAR(cache_mean / reference_mean, 1.0, tolerance);
}

}  // namespace
}  // namespace rcsplat
