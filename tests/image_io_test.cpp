// Image output: the EXR keeps linear floats and names its layers; non-finite values never reach a file.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "cli/commands.h"
#include "image/image_io.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

RenderedImage small_image() {
  RenderedImage img;
  img.width = 3;
  img.height = 2;
  size_t n = 6;
  for (std::vector<float>* layer : {&img.color, &img.direct, &img.emission, &img.albedo, &img.normal, &img.position})
    for (size_t i = 0; i < n * 3; ++i) layer->push_back(0.25f * float(i) + float(layer - &img.color));
  img.depth.assign(n, 2.0f);
  img.color[4] = NAN;
  img.color[5] = 1e30f;
  return img;
}

TEST(ImageIo, ExrRoundTripsLinearValuesWithLayers) {
  RenderedImage img = small_image();
  std::string path = test::scratch_dir() + "/out.exr";
  write_render(path, img, 0.0f);
  int w = 0, h = 0;
  std::vector<float> rgb = read_exr_rgb(path, w, h);
  ASSERT_EQ(w, 3);
  ASSERT_EQ(h, 2);
  for (size_t i = 0; i < rgb.size(); ++i) {
    if (i == 4) EXPECT_EQ(rgb[i], 0.0f);  // NaN was written as 0
    else EXPECT_EQ(rgb[i], img.color[i]);
  }
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  std::vector<std::string> names = in->spec().channelnames;
  for (const char* expected : {"direct.R", "emission.B", "albedo.G", "normal.X", "position.Z", "depth.Z"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
}

TEST(ImageIo, PngAndUnknownFormats) {
  RenderedImage img = small_image();
  std::string dir = test::scratch_dir();
  write_render(dir + "/out.png", img, 0.0f);
  EXPECT_TRUE(std::filesystem::exists(dir + "/out.png"));
  EXPECT_THROW(write_render(dir + "/out.bmp", img, 0.0f), Error);
  EXPECT_THROW(write_render(dir + "/missing-folder/out.exr", img, 0.0f), Error);
  // Only the PNG remains: no temporary files left behind by the failures.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// `rcsplat render` as a user runs it: the EXR carries the cache's layers, every value finite, and the summary JSON.
TEST(ImageIo, RenderCommandWritesTheCacheLayers) {
  std::string dir = test::scratch_dir();
  RenderOptions o;
  o.outputs = {dir + "/cornell.exr"};
  o.json_path = dir + "/summary.json";
  o.settings.width = o.settings.height = 40;
  o.settings.light_samples = 1;
  o.settings.cache.theta_strata = 4;
  o.settings.cache.phi_strata = 8;
  ASSERT_EQ(run_render(o), 0);
  auto in = OIIO::ImageInput::open(o.outputs[0]);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  for (const char* name : {"R", "direct.R", "indirect.R", "irradiance.G", "coverage.Y", "records.Y",
                           "record_positions.Y", "depth.Z"})
    EXPECT_NE(std::find(spec.channelnames.begin(), spec.channelnames.end(), name), spec.channelnames.end()) << name;
  std::vector<float> all(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()));
  for (float v : all) ASSERT_TRUE(std::isfinite(v));
  EXPECT_TRUE(std::filesystem::exists(o.json_path));
}

}  // namespace
}  // namespace rcsplat
