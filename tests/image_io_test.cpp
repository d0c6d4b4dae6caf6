// Image output: the EXR keeps linear floats and names its layers; non-finite values never reach a file.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <random>
#include <fstream>

#include "render/render_output.h"
#include "image/exr_file.h"
#include "image/image_io.h"
#include "render/render_output.h"
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

ExrPixels random_exr(int width, int height, std::vector<std::string> channels, uint32_t seed) {
  ExrPixels image{width, height, std::move(channels), {}, {{"rcsplat:note", "a string"}}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1e3f, 1e3f);
  image.values.resize(size_t(width) * size_t(height) * image.channels.size());
  for (float& v : image.values) v = value(rng);
  return image;
}

// rcsplat's own EXR writer (the one a build without OpenImageIO uses) against OpenImageIO as the independent reader,
// and its reader against OpenImageIO's uncompressed output: same channels, same bits, same string attributes. Channels
// are given out of alphabetical order, which the format forbids in the file.
TEST(ImageIo, UncompressedExrAgreesWithOpenImageIo) {
  ExrPixels image = random_exr(7, 5, {"Z", "R", "indirect.B", "a_long_layer_name_past_31_bytes.G"}, 3);
  std::string ours = test::scratch_dir() + "/ours.exr";
  write_uncompressed_exr(ours, image);
  ExrPixels by_oiio = read_exr_file(ours);
  ASSERT_EQ(by_oiio.width, 7);
  ASSERT_EQ(by_oiio.height, 5);
  EXPECT_EQ(by_oiio.text["rcsplat:note"], "a string");
  ASSERT_EQ(by_oiio.channels.size(), image.channels.size());
  for (size_t c = 0; c < image.channels.size(); ++c) {
    size_t k = size_t(std::find(by_oiio.channels.begin(), by_oiio.channels.end(), image.channels[c]) -
                      by_oiio.channels.begin());
    ASSERT_LT(k, by_oiio.channels.size()) << image.channels[c];
    for (size_t i = 0; i < 35; ++i)
      ASSERT_EQ(by_oiio.values[i * 4 + k], image.values[i * 4 + c]) << image.channels[c] << " pixel " << i;
  }

  std::string theirs = test::scratch_dir() + "/theirs.exr";
  OIIO::ImageSpec spec(7, 5, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = by_oiio.channels;
  spec.attribute("compression", "none");
  spec.attribute("rcsplat:note", "a string");
  auto out = OIIO::ImageOutput::create(theirs);
  ASSERT_TRUE(out && out->open(theirs, spec) && out->write_image(OIIO::TypeDesc::FLOAT, by_oiio.values.data()));
  out->close();
  ExrPixels read_back = read_uncompressed_exr(theirs);
  EXPECT_EQ(read_back.channels, by_oiio.channels);
  EXPECT_EQ(read_back.values, by_oiio.values);
  EXPECT_EQ(read_back.text["rcsplat:note"], "a string");
}

// Files the small reader cannot read are refused with a reason, never a crash: zip compression (OpenImageIO's
// default), and every truncation and many byte corruptions of a valid file.
TEST(ImageIo, UncompressedExrReaderRefusesWhatItCannotRead) {
  ExrPixels image = random_exr(4, 3, {"R", "G", "B"}, 4);
  std::string zipped = test::scratch_dir() + "/zip.exr";
  write_exr_file(zipped, image);
  try {
    read_uncompressed_exr(zipped);
    FAIL() << "a zip-compressed file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("compressed"), std::string::npos) << e.what();
  }
  std::string good = test::scratch_dir() + "/good.exr";
  write_uncompressed_exr(good, image);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::string bad = test::scratch_dir() + "/bad.exr";
  std::mt19937 rng(5);
  for (size_t trial = 0; trial < bytes.size() * 4; ++trial) {
    std::string damaged = bytes;
    if (trial < bytes.size()) damaged.resize(trial);
    else damaged[rng() % damaged.size()] = char(rng());
    std::ofstream(bad, std::ios::binary) << damaged;
    try {
      ExrPixels r = read_uncompressed_exr(bad);
      EXPECT_EQ(r.values.size(), size_t(r.width) * size_t(r.height) * r.channels.size());
    } catch (const Error&) {
    }
  }
}

TEST(ImageIo, PngAndUnknownFormats) {
  RenderedImage img = small_image();
  std::string dir = test::scratch_dir();
  write_render(dir + "/out.png", img, 0.0f);
  EXPECT_TRUE(std::filesystem::exists(dir + "/out.png"));
  EXPECT_THROW(write_render(dir + "/out.bmp", img, 0.0f), Error);
  EXPECT_THROW(write_render(dir + "/out.png/out.exr", img, 0.0f), Error) << "a folder under a file";
  // A folder that does not exist yet is made.
  write_render(dir + "/made/deeper/out.exr", img, 0.0f);
  EXPECT_TRUE(std::filesystem::exists(dir + "/made/deeper/out.exr"));
  // The PNG and the made folder remain: no temporary files left behind by the failures.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 2);
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// `rcsplat render` as a user runs it: the EXR carries the cache's layers, every value finite, and the summary JSON.
TEST(ImageIo, RenderCommandWritesTheCacheLayers) {
  std::string dir = test::scratch_dir();
  const test::CommandRun run =
      test::run_rcsplat(dir, {"render", "-o", "cornell.exr", "--json", "summary.json", "--width", "40", "--height",
                              "40", "--light-samples", "1", "--hemisphere", "4x8"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto in = OIIO::ImageInput::open(dir + "/cornell.exr");
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  for (const char* name : {"R", "direct.R", "indirect.R", "irradiance.G", "coverage.Y", "records.Y",
                           "record_positions.Y", "depth.Z"})
    EXPECT_NE(std::find(spec.channelnames.begin(), spec.channelnames.end(), name), spec.channelnames.end()) << name;
  std::vector<float> all(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()));
  for (float v : all) ASSERT_TRUE(std::isfinite(v));
  EXPECT_TRUE(std::filesystem::exists(dir + "/summary.json"));
}

}  // namespace
}  // namespace rcsplat
