// Records that follow the scene rather than the image (CacheSettings::placement_lines): the pixel spacings and reaches
// scale with the image's height above placement_lines, so a frame twice as tall places about the records of the
// smaller one, where without it it places more.
#include <gtest/gtest.h>

#include "cache/cache_settings.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "test_support.h"

using namespace rcsplat;

TEST(PlacementLines, ScalesSpacingsAndReachesAboveItsHeight) {
  CacheSettings c;
  c.placement_lines = 100;
  CacheSettings same = c;
  scale_placement_to_image(same, 100);
  EXPECT_EQ(same, c) << "an image no taller than placement_lines keeps the pixel settings";
  CacheSettings tall = c;
  scale_placement_to_image(tall, 300);
  EXPECT_FLOAT_EQ(tall.min_reach_pixels, 3.0f * c.min_reach_pixels);
  EXPECT_FLOAT_EQ(tall.max_reach_pixels, 3.0f * c.max_reach_pixels);
  EXPECT_EQ(tall.finest_spacing_pixels, 3 * c.finest_spacing_pixels);
  EXPECT_EQ(tall.coarsest_spacing_pixels, 3 * c.coarsest_spacing_pixels);
  CacheSettings off;
  CacheSettings off_tall = off;
  scale_placement_to_image(off_tall, 4000);
  EXPECT_EQ(off_tall, off) << "placement_lines 0 never scales";
}

TEST(PlacementLines, ATallerFramePlacesAboutTheSmallerFramesRecords) {
  RenderSettings s = test::one_bounce_one_sample();
  s.width = s.height = 48;
  const uint64_t small = render(test::gpu(), make_cornell_box(), s).stats.irradiance.records;
  s.width = s.height = 96;
  const uint64_t tall_default = render(test::gpu(), make_cornell_box(), s).stats.irradiance.records;
  s.cache.placement_lines = 48;
  const uint64_t tall_scaled = render(test::gpu(), make_cornell_box(), s).stats.irradiance.records;
  std::printf("records: 48 x 48 %llu; 96 x 96 %llu, with placement_lines 48 %llu\n", (unsigned long long)small,
              (unsigned long long)tall_default, (unsigned long long)tall_scaled);
  EXPECT_GT(double(tall_default), 1.5 * double(small));
  EXPECT_LT(double(tall_scaled), 1.3 * double(small));
  EXPECT_GT(double(tall_scaled), 0.7 * double(small));
}
