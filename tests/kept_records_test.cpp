// Irradiance records kept across frames (issue 42, item 2; render/kept_records.h): a still camera settles on the same
// bits, a kept record splats what it splatted when placed, a moved camera places records only where no kept one
// reaches, and eviction keeps the cap, least recently used first.
#include "render/kept_records.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/cache_math.h"
#include "passes/hsh_record_pass.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "lobed_cornell_box.h"
#include "test_support.h"

namespace rcsplat {
namespace {

RenderSettings kept_settings() {
  RenderSettings s = test::one_bounce_one_sample();
  s.width = s.height = 48;
  s.light_samples = 4;
  s.keep_records = true;
  return s;
}

// kept_settings with the scene's camera moved 0.08 to its right, still looking at its target.
RenderSettings moved_aside(const Scene& scene) {
  RenderSettings moved = kept_settings();
  const SceneCamera& camera = scene.cameras[0];
  moved.camera_overrides.eye = camera.eye + 0.08f * glm::normalize(glm::cross(camera.target - camera.eye, camera.up));
  moved.camera_overrides.target = camera.target;
  return moved;
}

TEST(KeptRecords, AStillCameraSettlesOnTheSameBitsAndItsFirstFrameIsAFreshOne) {
  const Scene scene = make_cornell_box();
  RenderSettings fresh = kept_settings();
  fresh.keep_records = false;
  const RenderedImage alone = render(test::gpu(), scene, fresh);
  Renderer renderer(test::gpu(), scene);
  std::vector<RenderedImage> frames;
  for (int f = 0; f < 4; ++f) frames.push_back(renderer.render(kept_settings()));
  EXPECT_EQ(frames[0].color, alone.color) << "nothing kept yet: a fresh frame";
  EXPECT_EQ(frames[0].stats.kept_records.reused, 0u);
  EXPECT_EQ(frames[1].stats.kept_records.reused, frames[0].stats.irradiance.records);
  // Placement may leave a few pixels uncovered (its last rounds at spacing 1); a later frame fills them, and once a
  // frame adds nothing, every frame after it is the same bits.
  int settled = -1;
  for (int f = 1; f < 4 && settled < 0; ++f)
    if (frames[size_t(f)].stats.kept_records.added == 0) settled = f;
  ASSERT_GE(settled, 1) << "still adding records after 4 frames of one view";
  for (size_t f = size_t(settled) + 1; f < frames.size(); ++f)
    EXPECT_EQ(frames[f].color, frames[size_t(settled)].color);
  EXPECT_LT(frames[1].stats.kept_records.added, frames[0].stats.irradiance.records / 20);
}

// A walkthrough whose frames ask for their colour alone (PNG frames: RenderSettings::color_only) keeps its records on
// the device but for the ones each frame adds: the same colour, the same kept records and the same summary counts as
// frames with every layer, with no record brought back for the image. Planted once: keeping the frame's first `added`
// records instead of its last failed the colour and the reuse of the frame that returns to the first view.
TEST(KeptRecords, AColourOnlyWalkthroughKeepsWhatAFullOneKeeps) {
  const Scene scene = make_cornell_box();
  Renderer full_frames(test::gpu(), scene), colour_frames(test::gpu(), scene);
  RenderSettings colour_only = kept_settings();
  colour_only.color_only = true;
  RenderSettings moved_colour_only = moved_aside(scene);
  moved_colour_only.color_only = true;
  const std::vector<std::pair<RenderSettings, RenderSettings>> frames = {
      {kept_settings(), colour_only}, {moved_aside(scene), moved_colour_only}, {kept_settings(), colour_only}};
  uint64_t clamped = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    const RenderedImage full = full_frames.render(frames[k].first);
    const RenderedImage colour = colour_frames.render(frames[k].second);
    EXPECT_EQ(colour.color, full.color) << "frame " << k;
    EXPECT_TRUE(colour.records.empty()) << "frame " << k;
    EXPECT_FALSE(full.records.empty()) << "frame " << k;
    const RenderStats &a = colour.stats, &b = full.stats;
    EXPECT_EQ(a.irradiance.records, b.irradiance.records) << "frame " << k;
    EXPECT_EQ(a.irradiance.at_min_radius, b.irradiance.at_min_radius) << "frame " << k;
    EXPECT_EQ(a.irradiance.at_max_radius, b.irradiance.at_max_radius) << "frame " << k;
    EXPECT_EQ(a.kept_records.reused, b.kept_records.reused) << "frame " << k;
    EXPECT_EQ(a.kept_records.added, b.kept_records.added) << "frame " << k;
    if (k == 1) EXPECT_GT(a.kept_records.added, 0u) << "the move shows something new";
    clamped += b.irradiance.at_min_radius + b.irradiance.at_max_radius;
  }
  EXPECT_GT(clamped, 0u) << "no reach at a clamp: the counts' comparison would prove nothing";
}

// The records a frame splats are the kept ones, as they were placed (the same view fits them to the same radii), and
// each pixel's irradiance is theirs: a frame that adds no record shows what the frame that placed them showed, up to
// the records that frame added to fill its last holes.
TEST(KeptRecords, AKeptRecordIsSplattedAsWhenItWasPlaced) {
  const Scene scene = make_cornell_box();
  Renderer renderer(test::gpu(), scene);
  const RenderedImage first = renderer.render(kept_settings());
  const RenderedImage second = renderer.render(kept_settings());
  ASSERT_GE(second.records.size(), first.records.size());
  for (size_t k = 0; k < first.records.size(); ++k) {
    EXPECT_EQ(second.records[k].radius, first.records[k].radius) << k;
    EXPECT_EQ(second.records[k].pixel, first.records[k].pixel) << k << ": seated where it was placed";
  }
  // Pixels no record added by the second frame reaches have the first frame's irradiance.
  size_t same = 0, compared = 0;
  for (size_t i = 0; i < size_t(first.width * first.height); ++i) {
    bool near_new = false;
    const glm::vec3 p(first.position[3 * i], first.position[3 * i + 1], first.position[3 * i + 2]);
    for (size_t k = first.records.size(); k < second.records.size() && !near_new; ++k) {
      const CacheRecord& r = second.records[k];
      near_new = glm::length(p - glm::vec3(r.position[0], r.position[1], r.position[2])) < 2.0f * r.radius;
    }
    if (near_new || first.depth[i] == 0.0f) continue;
    ++compared;
    same += first.irradiance[3 * i] == second.irradiance[3 * i] &&
            first.irradiance[3 * i + 1] == second.irradiance[3 * i + 1];
  }
  EXPECT_GT(compared, size_t(first.width * first.height) / 2);
  EXPECT_EQ(same, compared);
}

// After a small move, new records sit only where no kept record reaches (the splat's test, cache_math.h
// record_reaches, at the new record's own point and normal, with 2% margin on the weight for the float rounding of
// world units), and far fewer are placed than a fresh frame places.
TEST(KeptRecords, AMovedCameraPlacesRecordsOnlyWhereNoKeptRecordReaches) {
  const Scene scene = make_cornell_box();
  Renderer renderer(test::gpu(), scene);
  renderer.render(kept_settings());
  const RenderSettings moved = moved_aside(scene);
  const RenderedImage frame = renderer.render(moved);
  RenderSettings fresh = moved;
  fresh.keep_records = false;
  const RenderedImage alone = render(test::gpu(), scene, fresh);
  const size_t reused = frame.stats.kept_records.reused, added = frame.stats.kept_records.added;
  EXPECT_GT(reused, 0u);
  EXPECT_GT(added, 0u) << "the move shows something new";
  EXPECT_LT(added, alone.stats.irradiance.records / 3);
  const float accuracy = moved.cache.accuracy;
  size_t reached = 0;
  for (size_t k = reused; k < frame.records.size(); ++k) {
    const CacheRecord& r = frame.records[k];
    const rc_float3 p = {r.position[0], r.position[1], r.position[2]}, n = {r.normal[0], r.normal[1], r.normal[2]};
    for (size_t j = 0; j < reused; ++j) {
      const CacheRecord& old = frame.records[j];
      const rc_float3 pk = {old.position[0], old.position[1], old.position[2]};
      const rc_float3 nk = {old.normal[0], old.normal[1], old.normal[2]};
      rc_float3 tk, bk;
      tangent_frame(nk, &tk, &bk);
      const float w = ward_weight(p, n, pk, nk, old.radius);
      if (w > 1.02f / accuracy && record_reaches(&old, tk, bk, w, accuracy, p, n, pk, nk, old.radius)) ++reached;
    }
  }
  EXPECT_EQ(reached, 0u);
}

// Radiance records (the LOBE_HSH pixels) are kept with their HSH coefficients: a still camera's first frame is a fresh
// one, the next reuses every radiance record and, once it adds none, shows the same bits; a moved camera reuses them
// and adds few. Planted once: the brightest stratum not kept with the records (the splat's fixed-point scale) failed the
// second frame's bits; coefficients not loaded with the kept records are caught by the cache file's test (a fresh
// Renderer), since here the buffer still holds them in the same order.
TEST(KeptRecords, RadianceRecordsAreKeptWithTheirCoefficients) {
  const Scene scene = test::cornell_box_with_lobes(0.6f, 0.5f);
  RenderSettings fresh = kept_settings();
  fresh.keep_records = false;
  const RenderedImage alone = render(test::gpu(), scene, fresh);
  ASSERT_GT(alone.stats.radiance.records, 50u);
  Renderer renderer(test::gpu(), scene);
  std::vector<RenderedImage> frames;
  for (int f = 0; f < 4; ++f) frames.push_back(renderer.render(kept_settings()));
  EXPECT_EQ(frames[0].color, alone.color) << "nothing kept yet: a fresh frame";
  EXPECT_EQ(frames[1].stats.kept_radiance_records.reused, frames[0].stats.radiance.records);
  int settled = -1;
  for (int f = 1; f < 4 && settled < 0; ++f)
    if (frames[size_t(f)].stats.kept_radiance_records.added == 0 && frames[size_t(f)].stats.kept_records.added == 0)
      settled = f;
  ASSERT_GE(settled, 1) << "still adding records after 4 frames of one view";
  for (size_t f = size_t(settled) + 1; f < frames.size(); ++f) EXPECT_EQ(frames[f].color, frames[size_t(settled)].color);
  // Here the second frame adds nothing, so it splats exactly the first frame's records, refitted to the same view, at
  // the same fixed-point scale: the same bits.
  ASSERT_EQ(settled, 1);
  EXPECT_EQ(frames[1].color, frames[0].color);

  const RenderSettings moved = moved_aside(scene);
  const RenderedImage turned = renderer.render(moved);
  RenderSettings moved_fresh = moved;
  moved_fresh.keep_records = false;
  const RenderedImage turned_alone = render(test::gpu(), scene, moved_fresh);
  EXPECT_GT(turned.stats.kept_radiance_records.reused, 0u);
  EXPECT_LT(turned.stats.kept_radiance_records.added, turned_alone.stats.radiance.records / 3);
  // The reused lobes' light is the fresh frame's within the cache's error: mean indirect over the image within 3%.
  double kept_sum = 0.0, fresh_sum = 0.0;
  for (size_t i = 0; i < turned.indirect.size(); ++i) {
    kept_sum += turned.indirect[i];
    fresh_sum += turned_alone.indirect[i];
  }
  EXPECT_NEAR(kept_sum / fresh_sum, 1.0, 0.03);
}

// A kept radiance record whose fit to a new view grew its radius gets its translational gradients bounded for the new
// radius (kernels/hsh_records.cl bound_fitted_radiance_gradients), per channel |grad| <= |lambda| / R over the n^2
// coefficients; one whose radius did not grow keeps every float. Random records against a double-precision host
// reference; tolerance 2e-6 relative to each block's largest float (float sums of n^2 = 16 squares).
TEST(KeptRecords, AFitThatGrowsARadianceRecordsReachBoundsItsGradientsForIt) {
  const int order = 4, n2 = order * order;
  HshRecordPass hsh(test::gpu(), order);
  const size_t per = hsh.floats_per_record(), count = 64;
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f);
  std::vector<float> coefficients(count * per);
  for (float& c : coefficients) c = signed_unit(rng);
  std::vector<CacheRecord> records(count);
  std::vector<float> kept_radii(count);
  for (size_t i = 0; i < count; ++i) {
    kept_radii[i] = 1.0f + 3.0f * unit(rng);  // wide: unbounded, every gradient here would exceed the bound
    // A third grow (some enough to bind the bound, some not), a third shrink, a third stay.
    records[i].radius = i % 3 == 0 ? kept_radii[i] * (1.0f + 20.0f * unit(rng))
                        : i % 3 == 1 ? kept_radii[i] * 0.5f : kept_radii[i];
  }
  hsh.load(coefficients, uint32_t(count));
  const cl::Buffer on_device = test::gpu().upload(records, CL_MEM_READ_ONLY, "test records");
  hsh.bound_fitted_gradients(on_device, kept_radii);
  const std::vector<float> bounded = hsh.download(0, uint32_t(count));
  size_t scaled = 0;
  for (size_t i = 0; i < count; ++i) {
    const float* before = coefficients.data() + i * per;
    const float* after = bounded.data() + i * per;
    if (!(records[i].radius > kept_radii[i])) {
      for (size_t k = 0; k < per; ++k) ASSERT_EQ(after[k], before[k]) << "record " << i << " float " << k;
      continue;
    }
    double largest = 0.0;
    for (size_t k = 0; k < per; ++k) largest = std::max(largest, double(std::fabs(before[k])));
    for (int c = 0; c < 3; ++c) {
      double light = 0.0, change = 0.0;
      for (int k = 0; k < n2; ++k) {
        light += std::pow(double(before[(HSH_PART_COEFFICIENTS * n2 + k) * 3 + c]), 2);
        change += std::pow(double(before[(HSH_PART_GRADIENT_T * n2 + k) * 3 + c]), 2) +
                  std::pow(double(before[(HSH_PART_GRADIENT_B * n2 + k) * 3 + c]), 2);
      }
      const double limit = std::sqrt(light) / double(records[i].radius), norm = std::sqrt(change);
      const double scale = norm > limit ? limit / norm : 1.0;
      scaled += scale < 1.0;
      for (int part = 0; part < HSH_RECORD_PARTS; ++part)
        for (int k = 0; k < n2; ++k) {
          const size_t at = size_t((part * n2 + k) * 3 + c);
          const bool gradient = part == HSH_PART_GRADIENT_T || part == HSH_PART_GRADIENT_B;
          EXPECT_NEAR(after[at], double(before[at]) * (gradient ? scale : 1.0), 2e-6 * largest)
              << "record " << i << " part " << part << " coefficient " << k << " channel " << c;
        }
    }
  }
  EXPECT_GT(scaled, 10u) << "too few grown radii bound the gradients to test the bound";
}

CacheRecord record_at(float x, float y, float z) {
  CacheRecord r{};
  r.position[0] = x;
  r.position[1] = y;
  r.position[2] = z;
  r.normal[2] = 1.0f;
  r.radius = 0.01f;
  return r;
}

// A pinhole at the origin looking down -z, 90 degrees wide and high.
CameraParams look_down_minus_z() {
  CameraParams c{};
  c.forward[2] = -1.0f;
  c.right[0] = 1.0f;
  c.up[1] = 1.0f;
  c.tan_half_fov_y = 1.0f;
  c.aspect = 1.0f;
  c.width = c.height = 100;
  return c;
}

TEST(KeptRecords, AViewTakesTheRecordsItMaySeeAndEvictionDropsTheLeastRecentlyUsed) {
  KeptRecords kept(100);
  CacheSettings cache;
  kept.begin_frame({});
  std::vector<CacheRecord> first;
  // Every other record well outside the 90-degree view (|x| = 3 |z|), the rest on its axis.
  for (int i = 0; i < 80; ++i)
    first.push_back(record_at(i % 2 ? 3.0f * (1.0f + float(i)) : 0.0f, 0.0f, -1.0f - float(i)));
  kept.add(first.data(), first.size());
  EXPECT_EQ(kept.size(), 80u);
  EXPECT_EQ(kept.stats().evicted, 0u);

  kept.begin_frame({});
  CameraParams view = look_down_minus_z();
  const std::vector<CacheRecord> seen = kept.for_view(view, cache);
  // In view: |x| <= -z (90 degrees), give or take the reach.
  size_t expected = 0;
  for (const CacheRecord& r : first) expected += std::fabs(r.position[0]) <= -r.position[2];
  EXPECT_EQ(seen.size(), expected);
  EXPECT_EQ(expected, 40u);
  std::vector<CacheRecord> behind = {record_at(0.0f, 0.0f, 5.0f)};
  kept.add(behind.data(), 1);
  kept.begin_frame({});
  EXPECT_EQ(kept.for_view(view, cache).size(), expected) << "a record behind the camera is not taken";

  std::vector<CacheRecord> more(40, record_at(0.0f, 0.0f, -2.0f));
  kept.add(more.data(), more.size());  // 121 > 100: 21 go, all from those the last two frames did not see
  EXPECT_EQ(kept.size(), 100u);
  EXPECT_EQ(kept.stats().evicted, 21u);
  kept.begin_frame({});
  const std::vector<CacheRecord> after = kept.for_view(view, cache);
  EXPECT_EQ(after.size(), expected + 40) << "every record a recent view used is still kept";

  KeptRecordsKey other;
  other.seed = 1;
  kept.begin_frame(other);
  EXPECT_EQ(kept.size(), 0u) << "other settings: the records are dropped";
}

}  // namespace
}  // namespace rcsplat
