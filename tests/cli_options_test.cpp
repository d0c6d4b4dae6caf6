// The render options' parsers and `rcsplat compare`: good input works, bad input is refused with a message naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "render/settings_text.h"
#include "sequence/render_job.h"
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

// Runs `rcsplat compare IMAGE REFERENCE --json cmp.json` in dir and reads back the JSON it wrote.
nlohmann::json compare_json(const std::string& dir, const std::string& image, const std::string& reference) {
  const test::CommandRun run = test::run_rcsplat(dir, {"compare", image, reference, "--json", "cmp.json"});
  EXPECT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(dir + "/cmp.json");
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
  const nlohmann::json j = compare_json(dir, "b.exr", "a.exr");
  ASSERT_EQ(j["rendered_differently"].size(), 1u) << j.dump();
  EXPECT_EQ(j["rendered_differently"][0]["attribute"], "rcsplat:pixel_samples");
  EXPECT_EQ(j["rendered_differently"][0]["image"], "4");
  EXPECT_EQ(j["rendered_differently"][0]["reference"], "1");
  EXPECT_FALSE(j["finer_pixel_reference"]);

  // The image at 1 sample against the reference at 4.
  const nlohmann::json area = compare_json(dir, "a.exr", "b.exr");
  EXPECT_EQ(area["rendered_differently"].size(), 0u) << area.dump();
  EXPECT_TRUE(area["finer_pixel_reference"]);

  write_rgb_exr(dir + "/c.exr", 8, 6, 1.0f, true,
                {{"rcsplat:pixel_samples", "1"}, {"rcsplat:environment", "none"}, {"rcsplat:bounces", "3"}});
  const nlohmann::json bounces = compare_json(dir, "a.exr", "c.exr");
  ASSERT_EQ(bounces["rendered_differently"].size(), 1u) << bounces.dump();
  EXPECT_EQ(bounces["rendered_differently"][0]["attribute"], "rcsplat:bounces");
}

TEST(Compare, ReportsErrorsAndRefusesMismatchedImages) {
  std::string dir = test::scratch_dir();
  write_rgb_exr(dir + "/a.exr", 8, 6, 1.0f, true);
  write_rgb_exr(dir + "/b.exr", 8, 6, 1.1f, true);
  write_rgb_exr(dir + "/small.exr", 4, 6, 1.0f, true);
  const test::CommandRun run = test::run_rcsplat(
      dir, {"compare", "b.exr", "a.exr", "--heatmap", "heat.png", "--flip-heatmap", "flip.png", "--json", "cmp.json"});
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/heat.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/flip.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/cmp.json"));
  const nlohmann::json j = compare_json(dir, "b.exr", "a.exr");
  EXPECT_GT(j["full"]["mean_flip"].get<double>(), 0.0) << j.dump();
  EXPECT_LT(j["full"]["mean_flip"].get<double>(), 0.2) << j.dump();
  ErrorMetrics m = image_error(std::vector<float>(3, 1.1f), std::vector<float>(3, 1.0f));
  EXPECT_NEAR(m.rel_mse, 0.01 / 1.01, 1e-7);
  EXPECT_NEAR(m.rmse, 0.1, 1e-6);
  EXPECT_NEAR(m.mae, 0.1, 1e-6);

  const test::CommandRun mismatched = test::run_rcsplat(
      dir, {"compare", "b.exr", "small.exr", "--heatmap", "heat2.png", "--flip-heatmap", "flip2.png"});
  EXPECT_NE(mismatched.exit_code, 0) << "images of different sizes were compared";
  EXPECT_NE(mismatched.output.find("small.exr"), std::string::npos) << mismatched.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/heat2.png"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/flip2.png"));
  const test::CommandRun missing = test::run_rcsplat(dir, {"compare", "b.exr", "missing.exr"});
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("missing.exr"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// `rcsplat reference --resume`: the second run adds samples drawn with another seed and averages them in by count;
// what it writes is exactly the two parts' weighted mean, and a mismatched file is refused by name.
TEST(Reference, ResumeAddsIndependentSamples) {
  std::string dir = test::scratch_dir();
  const std::string ref = dir + "/ref.exr";
  // What the refusals below change: the frame, bounces, environment, pixel samples and points.
  using Options = std::map<std::string, std::string>;
  const Options base = {{"--width", "16"}, {"--height", "16"}, {"--bounces", "1"}, {"--pixel-samples", "1"}};
  auto run = [&](const std::string& spp, const Options& changed = {}) {
    Options options = base;
    for (const auto& [option, value] : changed) options[option] = value;
    std::vector<std::string> args = {"reference", "-o", "ref.exr", "--resume", "--spp", spp, "--light-samples", spp};
    for (const auto& [option, value] : options) {
      args.push_back(option);
      if (!value.empty()) args.push_back(value);  // a flag
    }
    return test::run_rcsplat(dir, args);
  };
  test::CommandRun r = run("8");  // no file yet: an ordinary first run
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int w = 0, h = 0;
  std::vector<float> first = read_exr_layer(ref, "indirect", w, h);
  r = run("24");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_exr_attributes(ref)["rcsplat:path_samples"], "24");
  std::vector<float> merged = read_exr_layer(ref, "indirect", w, h);

  RenderSettings second;
  second.width = second.height = 16;
  second.gi = GiMethod::path;
  second.path.stratified = true;
  second.bounces = second.pixel_samples = 1;
  second.path.samples = 16;
  second.light_samples = 16;
  second.seed = 8;  // the resumed part's seed: the first seed plus the samples before it
  RenderedImage part = render(test::gpu(), load_scene(""), second);
  for (size_t i = 0; i < merged.size(); ++i)
    ASSERT_NEAR(merged[i], (first[i] * 8.0f + part.indirect[i] * 16.0f) / 24.0f, 1e-6f) << i;

  // Another frame, bounce count, environment or pixel sampling: refused by name, and the file is left as it was.
  auto refused = [&](const Options& changed, const std::string& expected) {
    const test::CommandRun run32 = run("32", changed);
    EXPECT_NE(run32.exit_code, 0) << "resumed despite " << expected;
    EXPECT_NE(run32.output.find(expected), std::string::npos) << run32.output;
    EXPECT_EQ(read_exr_attributes(ref)["rcsplat:path_samples"], "24") << expected;
  };
  refused({{"--width", "8"}}, "is 16x16, this frame 8x16");
  refused({{"--bounces", "2"}}, "rendered with --bounces 1, not 2");
  refused({{"--sky", "0.5,0.5,0.5"}}, "rendered with environment none, not uniform sky (0.5, 0.5, 0.5)");
  refused({{"--pixel-samples", "4"}}, "rendered with --pixel-samples 1, not 4");
  refused({{"--sub-pixel-grid", ""}}, "rendered with pixel points jittered, not rotated grid");
}

// info runs the bounce probe a render runs (the built-in Cornell box keeps half of each reflection: 5 bounces) and
// says why not when it has no device, printing the rest.
TEST(Info, NamesTheBouncesARenderChooses) {
  const std::string dir = test::scratch_dir();
  test::CommandRun run = test::run_rcsplat(dir, {"info", "--json", "info.json"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/info.json"));
  EXPECT_EQ(j["bounces"]["chosen"], 5);
  EXPECT_NEAR(j["bounces"]["kept_per_bounce"].get<double>(), 0.50, 0.03);
  EXPECT_EQ(j["bounces"]["cache_method"], "photons");
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 8;
  settings.bounces = 0;
  EXPECT_EQ(render(test::gpu(), load_scene(""), settings).stats.bounces.count, 5u) << "what a render chooses";

  run = test::run_rcsplat(dir, {"info", "--json", "info.json", "--device", "no such device"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  j = nlohmann::json::parse(std::ifstream(dir + "/info.json"));
  EXPECT_TRUE(j["bounces"]["chosen"].is_null());
  EXPECT_NE(j["bounces"]["why_not"].get<std::string>().find("no such device"), std::string::npos);
  EXPECT_EQ(j["triangles"], 32);
}

}  // namespace
}  // namespace rcsplat
