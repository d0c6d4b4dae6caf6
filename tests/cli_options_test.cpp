// The render options' parsers and `rcsplat compare`: good input works, bad input is refused with a message naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "cli/commands.h"
#include "image/error_metrics.h"
#include "image/image_io.h"
#include "render/frame_plan.h"
#include "render/renderer.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

TEST(CliOptions, HemisphereAndSpacingParse) {
  CacheSettings c;
  parse_hemisphere("24x48", c);
  EXPECT_EQ(c.theta_strata, 24u);
  EXPECT_EQ(c.phi_strata, 48u);
  parse_spacing("2.5,15", c);
  EXPECT_FLOAT_EQ(c.min_reach_pixels, 2.5f);
  EXPECT_FLOAT_EQ(c.max_reach_pixels, 15.0f);
  EXPECT_EQ(parse_gi_method("octree"), GiMethod::octree);
  parse_hemisphere("8x16", c, true);
  EXPECT_EQ(c.fine_theta_strata, 8u);
  EXPECT_EQ(c.fine_phi_strata, 16u);
  EXPECT_EQ(c.theta_strata, 24u);
}

TEST(CliOptions, BadValuesAreRefusedByName) {
  // The command line parses; the plan's check_request refuses what is out of range, once, by the option's name.
  const std::pair<const char*, std::vector<const char*>> cases[] = {
      {"--hemisphere", {"16", "0x32", "16x0", "16x32x", "65x8", "ax8"}},
      {"--spacing", {"3", "20,3", "0,5", "a,b", "3,20,1"}}};
  for (const auto& [option, bad_values] : cases)
    for (const char* bad : bad_values) {
      try {
        RenderSettings s;
        if (std::string(option) == "--hemisphere") parse_hemisphere(bad, s.cache);
        else parse_spacing(bad, s.cache);
        check_request(s);
        ADD_FAILURE() << option << " " << bad << " was accepted";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
      }
    }
  EXPECT_THROW(parse_gi_method("photon"), Error);
  CacheSettings bad_accuracy;
  bad_accuracy.accuracy = -1.0f;
  EXPECT_THROW(validate_cache_settings(bad_accuracy), Error);
  CacheSettings bad_lines;
  bad_lines.placement_lines = -1;
  try {
    validate_cache_settings(bad_lines);
    ADD_FAILURE() << "--placement-lines -1 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--placement-lines"), std::string::npos) << e.what();
  }
  for (float bad : {-0.1f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    CacheSettings bad_adaptive;
    bad_adaptive.adaptive_error = bad;
    try {
      validate_cache_settings(bad_adaptive);
      ADD_FAILURE() << "--adaptive-rays " << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--adaptive-rays"), std::string::npos) << e.what();
    }
  }
}

void write_rgb_exr(const std::string& path, int w, int h, float value, bool with_indirect,
                   const ExrAttributes& attributes = {}) {
  std::vector<float> rgb(size_t(w) * size_t(h) * 3, value), indirect(rgb.size(), value * 0.5f);
  std::vector<ImageLayer> layers = {{"", {"R", "G", "B"}, &rgb}};
  if (with_indirect) layers.push_back({"indirect", {"R", "G", "B"}, &indirect});
  write_exr(path, w, h, layers, attributes);
}

// Runs compare and reads back the JSON it wrote.
nlohmann::json compare_json(const CompareOptions& o) {
  EXPECT_EQ(run_compare(o), 0);
  std::ifstream in(o.json_path);
  return nlohmann::json::parse(in);
}

// A reference of another environment, bounce count or coarser pixel sampling measures a difference, not an error:
// compare names it. A reference on a finer sub-pixel grid integrates the pixels' area more closely: an error, noted.
TEST(Compare, NamesWhatTheTwoRendersDidDifferently) {
  std::string dir = test::scratch_dir();
  write_rgb_exr(dir + "/a.exr", 8, 6, 1.0f, true,
                {{"rcsplat:pixel_samples", "1"}, {"rcsplat:environment", "none"}, {"rcsplat:bounces", "1"}});
  write_rgb_exr(dir + "/b.exr", 8, 6, 1.1f, true,
                {{"rcsplat:pixel_samples", "4"}, {"rcsplat:environment", "none"}, {"rcsplat:bounces", "1"}});
  CompareOptions o;
  o.image_path = dir + "/b.exr";
  o.reference_path = dir + "/a.exr";
  o.json_path = dir + "/cmp.json";
  const nlohmann::json j = compare_json(o);
  ASSERT_EQ(j["rendered_differently"].size(), 1u) << j.dump();
  EXPECT_EQ(j["rendered_differently"][0]["attribute"], "rcsplat:pixel_samples");
  EXPECT_EQ(j["rendered_differently"][0]["image"], "4");
  EXPECT_EQ(j["rendered_differently"][0]["reference"], "1");
  EXPECT_FALSE(j["finer_pixel_reference"]);

  std::swap(o.image_path, o.reference_path);  // the image at 1 sample against the reference at 4
  const nlohmann::json area = compare_json(o);
  EXPECT_EQ(area["rendered_differently"].size(), 0u) << area.dump();
  EXPECT_TRUE(area["finer_pixel_reference"]);

  write_rgb_exr(dir + "/c.exr", 8, 6, 1.0f, true,
                {{"rcsplat:pixel_samples", "1"}, {"rcsplat:environment", "none"}, {"rcsplat:bounces", "3"}});
  o.reference_path = dir + "/c.exr";
  const nlohmann::json bounces = compare_json(o);
  ASSERT_EQ(bounces["rendered_differently"].size(), 1u) << bounces.dump();
  EXPECT_EQ(bounces["rendered_differently"][0]["attribute"], "rcsplat:bounces");
}

TEST(Compare, ReportsErrorsAndRefusesMismatchedImages) {
  std::string dir = test::scratch_dir();
  write_rgb_exr(dir + "/a.exr", 8, 6, 1.0f, true);
  write_rgb_exr(dir + "/b.exr", 8, 6, 1.1f, true);
  write_rgb_exr(dir + "/small.exr", 4, 6, 1.0f, true);
  CompareOptions o;
  o.image_path = dir + "/b.exr";
  o.reference_path = dir + "/a.exr";
  o.heatmap_path = dir + "/heat.png";
  o.json_path = dir + "/cmp.json";
  o.flip_heatmap_path = dir + "/flip.png";
  EXPECT_EQ(run_compare(o), 0);
  EXPECT_TRUE(std::filesystem::exists(o.heatmap_path));
  EXPECT_TRUE(std::filesystem::exists(o.flip_heatmap_path));
  EXPECT_TRUE(std::filesystem::exists(o.json_path));
  const nlohmann::json j = compare_json(o);
  EXPECT_GT(j["full"]["mean_flip"].get<double>(), 0.0) << j.dump();
  EXPECT_LT(j["full"]["mean_flip"].get<double>(), 0.2) << j.dump();
  ErrorMetrics m = image_error(std::vector<float>(3, 1.1f), std::vector<float>(3, 1.0f));
  EXPECT_NEAR(m.rel_mse, 0.01 / 1.01, 1e-7);
  EXPECT_NEAR(m.rmse, 0.1, 1e-6);
  EXPECT_NEAR(m.mae, 0.1, 1e-6);

  o.reference_path = dir + "/small.exr";
  o.heatmap_path = dir + "/heat2.png";
  o.flip_heatmap_path = dir + "/flip2.png";
  try {
    run_compare(o);
    ADD_FAILURE() << "images of different sizes were compared";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("small.exr"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(o.heatmap_path));
  EXPECT_FALSE(std::filesystem::exists(o.flip_heatmap_path));
  o.reference_path = dir + "/missing.exr";
  EXPECT_THROW(run_compare(o), Error);
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// `rcsplat reference --resume`: the second run adds samples drawn with another seed and averages them in by count;
// what it writes is exactly the two parts' weighted mean, and a mismatched file is refused by name.
TEST(Reference, ResumeAddsIndependentSamples) {
  std::string dir = test::scratch_dir();
  RenderOptions o;
  o.outputs = {dir + "/ref.exr"};
  o.settings.width = o.settings.height = 16;
  o.settings.gi = GiMethod::path;
  o.settings.path.stratified = true;
  o.settings.path.samples = o.settings.light_samples = 8;
  o.settings.bounces = o.settings.pixel_samples = 1;  // what the refusals below change
  o.resume = true;  // no file yet: an ordinary first run
  ASSERT_EQ(run_render(o), 0);
  int w = 0, h = 0;
  std::vector<float> first = read_exr_layer(o.outputs[0], "indirect", w, h);
  o.settings.path.samples = o.settings.light_samples = 24;
  ASSERT_EQ(run_render(o), 0);
  EXPECT_EQ(read_exr_attributes(o.outputs[0])["rcsplat:path_samples"], "24");
  std::vector<float> merged = read_exr_layer(o.outputs[0], "indirect", w, h);

  RenderSettings second = o.settings;
  second.path.samples = 16;
  second.light_samples = 16;
  second.seed = 8;  // the resumed part's seed: the first seed plus the samples before it
  RenderedImage part = render(test::gpu(), load_scene(""), second);
  for (size_t i = 0; i < merged.size(); ++i)
    ASSERT_NEAR(merged[i], (first[i] * 8.0f + part.indirect[i] * 16.0f) / 24.0f, 1e-6f) << i;

  o.settings.path.samples = 32;
  // Another frame, bounce count, environment or pixel sampling: refused by name, and the file is left as it was.
  auto refused = [&](RenderOptions changed, const std::string& expected) {
    try {
      run_render(changed);
      ADD_FAILURE() << "resumed despite " << expected;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
    EXPECT_EQ(read_exr_attributes(o.outputs[0])["rcsplat:path_samples"], "24") << expected;
  };
  RenderOptions narrower = o;
  narrower.settings.width = 8;
  refused(narrower, "is 16x16, this frame 8x16");
  RenderOptions bounces = o;
  bounces.settings.bounces = 2;
  refused(bounces, "rendered with --bounces 1, not 2");
  RenderOptions sky = o;
  sky.environment.sky = glm::vec3(0.5f);
  refused(sky, "rendered with environment none, not uniform sky (0.5, 0.5, 0.5)");
  RenderOptions anti_aliased = o;
  anti_aliased.settings.pixel_samples = 4;
  refused(anti_aliased, "rendered with --pixel-samples 1, not 4");
  RenderOptions grid = o;
  grid.settings.path.pixel_area = false;
  refused(grid, "rendered with pixel points jittered, not rotated grid");
}

// info runs the bounce probe a render runs (the built-in Cornell box keeps half of each reflection: 5 bounces) and
// says why not when it has no device, printing the rest.
TEST(Info, NamesTheBouncesARenderChooses) {
  const std::string dir = test::scratch_dir();
  InfoOptions o;
  o.json_path = dir + "/info.json";
  ASSERT_EQ(run_info(o), 0);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(o.json_path));
  EXPECT_EQ(j["bounces"]["chosen"], 5);
  EXPECT_NEAR(j["bounces"]["kept_per_bounce"].get<double>(), 0.50, 0.03);
  EXPECT_EQ(j["bounces"]["cache_method"], "photons");
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 8;
  settings.bounces = 0;
  EXPECT_EQ(render(test::gpu(), load_scene(""), settings).stats.bounces.count, 5u) << "what a render chooses";

  o.device = "no such device";
  ASSERT_EQ(run_info(o), 0);
  j = nlohmann::json::parse(std::ifstream(o.json_path));
  EXPECT_TRUE(j["bounces"]["chosen"].is_null());
  EXPECT_NE(j["bounces"]["why_not"].get<std::string>().find("no such device"), std::string::npos);
  EXPECT_EQ(j["triangles"], 32);
}

}  // namespace
}  // namespace rcsplat
