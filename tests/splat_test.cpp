// The splat (kernels/splat.cl): its screen footprint holds every pixel a record reaches (brute force over all pixels),
// it interpolates what a direct evaluation of Ward's formula gives (records spanning eight decades of irradiance, so
// the fixed-point sums keep dim values beside bright ones), and it is deterministic. And the paper's claim:
// for the same records, splatting gives the classic octree lookup's image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "cache/octree_lookup.h"
#include "cache_test_scenes.h"
#include "test_support.h"
#include "passes/gbuffer_pass.h"
#include "passes/splat_pass.h"
#include "render/camera.h"
#include "scene/scene_frame.h"
#include "render/placement.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"

namespace rcsplat {
namespace {

using glm::dvec3;
using glm::vec3;

vec3 position_of(const GBufferSample& g) { return {g.position[0], g.position[1], g.position[2]}; }
vec3 normal_of(const GBufferSample& g) { return {g.normal[0], g.normal[1], g.normal[2]}; }

// E_k(P) = max(0, E + (nk x n) . grad_r + (P - Pk) . grad_t) in double: the test's own reference, written apart from
// kernels/cache_math.h on purpose.
dvec3 reference_extrapolation(const CacheRecord& r, const dvec3& p, const dvec3& n) {
  dvec3 dp = p - dvec3(record_position(r)), dn = glm::cross(dvec3(record_normal(r)), n);
  dvec3 e(r.irradiance[0], r.irradiance[1], r.irradiance[2]);
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 3; ++c)
      e[c] += dp[axis] * r.grad_translation[3 * axis + c] + dn[axis] * r.grad_rotation[3 * axis + c];
  return glm::max(e, dvec3(0.0));
}

// A decision within 1e-5 (relative) of its threshold may go either way in float (the kernel's length() and the
// host's need not round alike); such pixels are left out and counted.
bool ambiguous(const CacheRecord& r, const GBufferSample& g, float accuracy) {
  vec3 p = position_of(g), n = normal_of(g), pk = record_position(r), nk = record_normal(r);
  float w = ward_weight(p, n, pk, nk, r.radius);
  float in_front = glm::dot(p - pk, n + nk) * 0.5f + IN_FRONT_TOLERANCE * r.radius;
  if (std::abs(w * accuracy - 1.0f) < 1e-5f) return true;
  return w * accuracy > 1.0f &&
         (std::abs(glm::dot(n, nk)) < 1e-6f || std::abs(in_front) < 1e-6f * (r.radius + glm::length(p - pk)));
}

// For a camera (perspective or orthographic), random records over its G-buffer: every pixel a record reaches lies in
// its footprint, and the splat's values are Ward's formula evaluated directly.
void check_footprints_and_values(test::TwinScene& twin, const SceneCamera& cam) {
  GpuContext& gpu = test::gpu();
  const int w = 96, h = 72;
  GBufferPass gbuffer(gpu, twin.device);
  gbuffer.run(camera_params(cam, w, h));
  std::vector<GBufferSample> g = gbuffer.download();
  float diagonal = glm::length(twin.scene.bounds_max() - twin.scene.bounds_min());

  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (float accuracy : {0.2f, 0.5f, 1.5f}) {
    // Records on visible surfaces with perturbed normals, radii from a tenth of a pixel to more than the scene (the
    // camera then sits inside some spheres), random irradiance and gradients.
    std::vector<CacheRecord> records(300);
    for (CacheRecord& r : records) {
      const GBufferSample* s;
      do s = &g[rng() % g.size()];
      while (s->triangle < 0);
      vec3 n = glm::normalize(normal_of(*s) + 0.4f * vec3(uni(rng) - 0.5f, uni(rng) - 0.5f, uni(rng) - 0.5f));
      std::memset(&r, 0, sizeof r);
      for (float& h : r.horizon) h = INFINITY;  // nothing hides anything from these records
      r.radius = diagonal * std::pow(10.0f, -3.5f + 3.6f * uni(rng));
      for (int i = 0; i < 3; ++i) {
        r.position[i] = s->position[i];
        r.normal[i] = n[i];
        r.irradiance[i] = std::pow(10.0f, -4.0f + 8.0f * uni(rng));  // eight decades in one frame
        for (int a = 0; a < 3; ++a) {  // within the bounds the record kernel enforces (|grad_t| R <= E, |grad_r| <= E)
          r.grad_translation[3 * a + i] = 0.5f * (uni(rng) - 0.5f) * r.irradiance[i] / r.radius;
          r.grad_rotation[3 * a + i] = 0.5f * (uni(rng) - 0.5f) * r.irradiance[i];
        }
      }
    }
    SplatPass splat(gpu);
    splat.splat_all(gbuffer.view(), gpu.upload(records), uint32_t(records.size()), accuracy);
    splat.resolve(gbuffer.view());
    std::vector<uint32_t> counts = splat.records_per_pixel();
    std::vector<float> irradiance = splat.irradiance_rgbw();

    size_t reached = 0, skipped = 0;
    for (size_t i = 0; i < g.size(); ++i) {
      if (g[i].triangle < 0) {
        EXPECT_EQ(counts[i], 0u);
        continue;
      }
      vec3 p = position_of(g[i]), n = normal_of(g[i]);
      uint32_t expected = 0;
      dvec3 sum(0.0);
      double weights = 0.0;
      bool unsure = false;
      for (const CacheRecord& r : records) {
        unsure = unsure || ambiguous(r, g[i], accuracy);
        float wk = ward_weight(p, n, record_position(r), record_normal(r), r.radius);
        if (!record_usable(wk, accuracy, p, n, record_position(r), record_normal(r), r.radius)) continue;
        ++expected;
        sum += double(wk) * reference_extrapolation(r, dvec3(p), dvec3(n));
        weights += wk;
      }
      if (unsure) {
        ++skipped;
        continue;
      }
      reached += expected;
      ASSERT_EQ(counts[i], expected) << "pixel " << i % w << "," << i / w << " at a = " << accuracy;
      for (int c = 0; c < 3 && expected; ++c)
        ASSERT_NEAR(irradiance[4 * i + size_t(c)], sum[c] / weights, 1e-5 * sum[c] / weights + 1e-7)
            << "pixel " << i << " channel " << c;
    }
    EXPECT_GT(reached, g.size() / 10) << "the random records should reach many pixels";
    EXPECT_LT(skipped, g.size() / 100) << skipped << " pixels at a threshold";

    // Coincident records (issue 10 part 5): every record twice, at the same point with the same radius. The fixed-point
    // sums double exactly, so every pixel's irradiance is the same bits and its count doubles.
    std::vector<CacheRecord> twice = records;
    twice.insert(twice.end(), records.begin(), records.end());
    SplatPass doubled(gpu);
    doubled.splat_all(gbuffer.view(), gpu.upload(twice), uint32_t(twice.size()), accuracy);
    doubled.resolve(gbuffer.view());
    std::vector<uint32_t> twice_counts = doubled.records_per_pixel();
    std::vector<float> twice_irradiance = doubled.irradiance_rgbw();
    for (size_t i = 0; i < g.size(); ++i) {
      ASSERT_EQ(twice_counts[i], 2 * counts[i]) << "pixel " << i;
      for (size_t c = 0; c < 3; ++c) ASSERT_EQ(twice_irradiance[4 * i + c], irradiance[4 * i + c]) << "pixel " << i;
    }
  }
}

TEST(Splat, FootprintHoldsEveryReachedPixelAndValuesMatchDirectEvaluation) {
  test::TwinScene twin(make_cornell_box());
  SceneCamera cam = choose_camera(twin.scene, 0, {});
  check_footprints_and_values(twin, cam);
  SceneCamera ortho = cam;  // the same view, orthographic, framing most of the box
  ortho.orthographic = true;
  ortho.ymag = 0.35f * glm::length(twin.scene.bounds_max() - twin.scene.bounds_min());
  check_footprints_and_values(twin, ortho);
}

RenderSettings small_splat(int size) {
  RenderSettings s = test::one_bounce_one_sample();
  s.width = s.height = size;
  s.gi = GiMethod::splat;
  s.light_samples = 4;
  s.cache.theta_strata = 8;
  s.cache.phi_strata = 16;
  return s;
}

TEST(Splat, SameInputSameBits) {
  Scene scene = make_cornell_box();
  RenderedImage a = render(test::gpu(), scene, small_splat(64));
  RenderedImage b = render(test::gpu(), scene, small_splat(64));
  ASSERT_GT(a.stats.irradiance.records, 0u);
  EXPECT_EQ(a.stats.irradiance.records, b.stats.irradiance.records);
  EXPECT_EQ(0, std::memcmp(a.irradiance.data(), b.irradiance.data(), a.irradiance.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(float)));
  for (float v : a.color) ASSERT_TRUE(std::isfinite(v));
  // The same records in the same order: each placement batch lists its candidates tile by tile (kernels/placement.cl
  // candidate_cell, written again here), whatever order work items run in (an atomic counter made that order differ
  // between runs). A level is one batch but the finest, which runs kRoundsAtFinestSpacing rounds at most.
  ASSERT_EQ(a.records.size(), b.records.size());
  EXPECT_EQ(0, std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(CacheRecord)));
  const int width = 64;  // small_splat(64), one sample a pixel
  size_t first = 0;
  const std::vector<PlacementLevel>& levels = a.stats.irradiance.levels;
  for (size_t l = 0; l < levels.size(); ++l) {
    const int spacing = levels[l].spacing_pixels;
    const uint32_t tiles_x = uint32_t((width + spacing - 1) / spacing + CANDIDATE_TILE - 1) / CANDIDATE_TILE;
    auto cell_of = [&](int pixel) {
      const uint32_t gx = uint32_t(pixel % width / spacing), gy = uint32_t(pixel / width / spacing);
      const uint32_t tile = (gy / CANDIDATE_TILE) * tiles_x + gx / CANDIDATE_TILE;
      return (tile * CANDIDATE_TILE + gy % CANDIDATE_TILE) * CANDIDATE_TILE + gx % CANDIDATE_TILE;
    };
    size_t descents = 0;
    for (size_t i = first + 1; i < first + levels[l].records; ++i)
      descents += cell_of(a.records[i].pixel) < cell_of(a.records[i - 1].pixel);
    EXPECT_LE(descents, l + 1 == levels.size() ? size_t(kRoundsAtFinestSpacing) - 1 : 0u) << "spacing " << spacing;
    first += levels[l].records;
  }
  EXPECT_EQ(first, a.records.size());
}

// Gautron et al.'s central claim: splatting each record over its footprint and normalising gives, pixel for pixel,
// what Ward's lookup of every record with w > 1/a (through an octree) gives, for the same records.
TEST(Splat, EqualsClassicOctreeLookupForTheSameRecords) {
  // In its own device frame, so that the records and positions the image gives back are the device's bits.
  Scene scene = SceneFrame::fitted(make_cornell_box()).device_scene(make_cornell_box());
  RenderSettings settings = small_splat(96);
  RenderedImage img = render(test::gpu(), scene, settings);
  const std::vector<CacheRecord>& records = img.records;
  ASSERT_GT(records.size(), 100u);
  float accuracy = settings.cache.accuracy;
  RecordOctree octree(dvec3(scene.bounds_min()), dvec3(scene.bounds_max()));
  for (size_t k = 0; k < records.size(); ++k)
    octree.insert(uint32_t(k), dvec3(record_position(records[k])), double(accuracy) * records[k].radius);
  double largest = 0.0;
  for (float v : img.irradiance) largest = std::max(largest, double(v));
  size_t compared = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    PixelGeometry geo{vec3(img.position[3 * i], img.position[3 * i + 1], img.position[3 * i + 2]),
                      vec3(img.normal[3 * i], img.normal[3 * i + 1], img.normal[3 * i + 2]), true};
    Interpolation lookup = interpolate(octree, records, geo, accuracy);
    ASSERT_GT(lookup.weight, 0.0) << "pixel " << i << " is covered by the splat but not by the lookup";
    ASSERT_EQ(uint32_t(img.records_per_pixel[i]), lookup.count) << "pixel " << i;
    for (int c = 0; c < 3; ++c) {
      double expected = lookup.weighted[c] / lookup.weight;
      ASSERT_NEAR(img.irradiance[3 * i + size_t(c)], expected, 1e-5 * expected + 1e-7 * largest) << "pixel " << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, img.triangle.size() / 2);
}

// The two cache methods run one placement loop over the same records (render/placement.h): they must place exactly
// the same records, at the same pixels, with the same clamped radii, level for level. Their images then differ only
// by float rounding (the octree sums in double, the splat in fixed point).
void expect_same_placement(const Scene& scene, RenderSettings settings) {
  settings.gi = GiMethod::splat;
  RenderedImage splat = render(test::gpu(), scene, settings);
  settings.gi = GiMethod::octree;
  RenderedImage octree = render(test::gpu(), scene, settings);
  ASSERT_GT(splat.stats.irradiance.records, 100u);
  ASSERT_EQ(octree.stats.irradiance.records, splat.stats.irradiance.records);
  ASSERT_EQ(octree.stats.irradiance.levels.size(), splat.stats.irradiance.levels.size());
  for (size_t l = 0; l < splat.stats.irradiance.levels.size(); ++l) {
    EXPECT_EQ(octree.stats.irradiance.levels[l].spacing_pixels, splat.stats.irradiance.levels[l].spacing_pixels);
    EXPECT_EQ(octree.stats.irradiance.levels[l].records, splat.stats.irradiance.levels[l].records) << "level " << l;
  }
  EXPECT_EQ(octree.record_positions, splat.record_positions);
  // Candidates are compacted with an atomic counter on the device, so records are compared by their pixel.
  auto by_pixel = [](std::vector<CacheRecord> r) {
    std::sort(r.begin(), r.end(), [](const CacheRecord& a, const CacheRecord& b) { return a.pixel < b.pixel; });
    return r;
  };
  std::vector<CacheRecord> a = by_pixel(splat.records), b = by_pixel(octree.records);
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].pixel, b[k].pixel);
    ASSERT_EQ(a[k].radius, b[k].radius) << "record at pixel " << a[k].pixel;
    ASSERT_EQ(0, std::memcmp(a[k].irradiance, b[k].irradiance, sizeof a[k].irradiance));
  }
  EXPECT_EQ(octree.records_per_pixel, splat.records_per_pixel);
  double largest = 0.0;
  for (float v : splat.indirect) largest = std::max(largest, double(v));
  for (size_t i = 0; i < splat.indirect.size(); ++i)
    ASSERT_NEAR(octree.indirect[i], splat.indirect[i], 1e-5 * splat.indirect[i] + 1e-7 * largest) << "value " << i;
}

TEST(Splat, OctreeMethodPlacesTheSameRecords) {
  expect_same_placement(make_cornell_box(), small_splat(96));
  Scene orthographic = make_cornell_box();  // records sized by an orthographic camera's constant pixel size
  SceneCamera plan = orthographic.cameras.front();
  plan.orthographic = true;
  plan.ymag = 0.3f * glm::length(orthographic.bounds_max() - orthographic.bounds_min());
  orthographic.cameras.push_back(plan);
  RenderSettings plan_settings = small_splat(64);
  plan_settings.camera = 1;
  expect_same_placement(orthographic, plan_settings);
  // Finer accuracy and a wider reach range: more neighbour clamping, so the repair rounds at spacing 1 place records.
  RenderSettings fine = small_splat(64);
  fine.cache.accuracy = 0.15f;
  fine.cache.min_reach_pixels = 1.5f;
  fine.cache.max_reach_pixels = 40.0f;
  expect_same_placement(make_cornell_box(), fine);
  // Sub-pixels: records sit one output pixel apart, and the device's neighbour clamping reads only that grid.
  RenderSettings anti_aliased = fine;
  anti_aliased.width = anti_aliased.height = 48;
  anti_aliased.pixel_samples = 4;
  expect_same_placement(make_cornell_box(), anti_aliased);
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// At the finest accuracy offered every pixel may need a record of its own, and never more than one.
TEST(Splat, AtMostOneRecordPerPixelAndEveryPixelCovered) {
  Scene scene = make_cornell_box();
  RenderSettings settings = small_splat(24);
  settings.cache.accuracy = 0.01f;
  RenderedImage img = render(test::gpu(), scene, settings);
  size_t marked = 0, with_geometry = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    marked += img.record_positions[i] > 0.0f;
    if (img.triangle[i] < 0) continue;
    ++with_geometry;
    EXPECT_GT(img.coverage[i], 0.0f) << "pixel " << i << " is uncovered";
  }
  EXPECT_EQ(img.stats.irradiance.records, marked);
  EXPECT_LE(img.stats.irradiance.records, with_geometry);
  EXPECT_EQ(img.stats.irradiance.uncovered_pixels, 0u);
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

std::vector<CacheRecord> records_by_pixel(std::vector<CacheRecord> r) {
  std::sort(r.begin(), r.end(), [](const CacheRecord& a, const CacheRecord& b) { return a.pixel < b.pixel; });
  return r;
}

void expect_same_records_and_image(const RenderedImage& a, const RenderedImage& b, const char* what) {
  std::vector<CacheRecord> ra = records_by_pixel(a.records), rb = records_by_pixel(b.records);
  ASSERT_EQ(ra.size(), rb.size()) << what;
  for (size_t k = 0; k < ra.size(); ++k)
    ASSERT_EQ(0, std::memcmp(&ra[k], &rb[k], sizeof(CacheRecord))) << what << ": record at pixel " << ra[k].pixel;
  EXPECT_EQ(a.indirect, b.indirect) << what;
}

// Adaptive rays trace every record with half the strata each way first and again with all of them where its error
// score is above the threshold: at a threshold nothing passes, the frame is the full hemisphere's, bit for bit; at one
// everything passes, the half hemisphere's; in between, some records are traced again.
TEST(Splat, AdaptiveRaysGiveTheFullOrTheHalfHemispheresRecords) {
  Scene scene = make_cornell_box();
  RenderSettings full = small_splat(64), half = small_splat(64);
  half.cache.theta_strata /= 2;
  half.cache.phi_strata /= 2;
  RenderedImage full_img = render(test::gpu(), scene, full), half_img = render(test::gpu(), scene, half);

  RenderSettings strict = full;
  strict.cache.adaptive_error = 1e-12f;
  RenderedImage strict_img = render(test::gpu(), scene, strict);
  EXPECT_EQ(strict_img.stats.irradiance.adaptive_records, strict_img.stats.irradiance.records);
  expect_same_records_and_image(strict_img, full_img, "every record traced again");

  RenderSettings lax = full;
  lax.cache.adaptive_error = 1e30f;
  RenderedImage lax_img = render(test::gpu(), scene, lax);
  EXPECT_EQ(lax_img.stats.irradiance.adaptive_records, 0u);
  expect_same_records_and_image(lax_img, half_img, "no record traced again");

  RenderSettings between = full;
  between.cache.adaptive_error = 0.3f;
  RenderedImage between_img = render(test::gpu(), scene, between);
  EXPECT_GT(between_img.stats.irradiance.adaptive_records, between_img.stats.irradiance.records / 10);
  EXPECT_LT(between_img.stats.irradiance.adaptive_records, between_img.stats.irradiance.records * 9 / 10);
  std::printf("adaptive rays at 0.3: %llu of %llu records traced again\n",
              (unsigned long long)between_img.stats.irradiance.adaptive_records,
              (unsigned long long)between_img.stats.irradiance.records);
}

// --short-ray-paths: a short record ray continues its path one bounce and reads the map there without its last
// landing. With two bounces that map is empty, so with every ray counted short the frame is --bounce-method path's,
// bit for bit (same random numbers, same code); with none, every ray reads the map; the default
// (two gather radii) continues some of them, so its records are neither's.
TEST(Splat, ShortRayPathsSpanThePathAndPhotonGathers) {
  Scene scene = make_cornell_box();
  RenderSettings path = small_splat(64);
  path.bounces = 2;
  path.bounce_method = BounceMethod::path;
  RenderSettings all_short = path, none_short = path, default_short = path;
  for (RenderSettings* s : {&all_short, &none_short, &default_short}) s->bounce_method = BounceMethod::photons;
  all_short.short_ray_paths = 1e6f;
  none_short.short_ray_paths = 0.0f;
  RenderedImage path_img = render(test::gpu(), scene, path), all_img = render(test::gpu(), scene, all_short);
  ASSERT_GT(all_img.stats.photon_map.photons, 0u);
  EXPECT_EQ(all_img.stats.irradiance.rays, path_img.stats.irradiance.rays);
  expect_same_records_and_image(all_img, path_img, "every record ray continues a bounce (two bounces: the path's)");

  RenderedImage none_img = render(test::gpu(), scene, none_short);
  RenderedImage default_img = render(test::gpu(), scene, default_short);
  EXPECT_LT(none_img.stats.irradiance.rays, default_img.stats.irradiance.rays);
  EXPECT_LT(default_img.stats.irradiance.rays, all_img.stats.irradiance.rays);
  std::printf("record rays: map only %llu, short rays continued %llu, every ray continued %llu\n",
              (unsigned long long)none_img.stats.irradiance.rays, (unsigned long long)default_img.stats.irradiance.rays,
              (unsigned long long)all_img.stats.irradiance.rays);
}

}  // namespace
}  // namespace rcsplat
