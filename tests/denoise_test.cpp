// --denoise (issue 59 item 2): Intel Open Image Denoise loaded at run time (image/denoiser.h) and a frame's
// per-pixel layers denoised and composed again with the cache's light (render/denoise_frame.h). The library comes
// from scripts/install-oidn.sh, which the setup script runs; where it is absent the tests that need it skip, saying so.
// scripts/sanitize.sh leaves the OpenImageDenoise suite out: the library is not instrumented (as PoCL is not).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "image/denoiser.h"
#include "render/denoise_frame.h"
#include "render/renderer.h"
#include "caustic_room_scene.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

std::unique_ptr<Denoiser> load_or_null(std::string* why) {
  try {
    return Denoiser::load();
  } catch (const Error& e) {
    *why = e.what();
    return nullptr;
  }
}

double mean_luminance(const std::vector<float>& rgb) {
  double sum = 0.0;
  for (size_t i = 0; i < rgb.size(); i += 3) sum += 0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2];
  return sum / double(rgb.size() / 3);
}

// An image whose truth is known: a checkered albedo (the guide) times a smooth light, with multiplicative noise of
// standard deviation 0.5 (a few samples' worth). The filter must take out most of the noise (the squared error to the
// truth at most a fifth of the noisy image's) and keep the mean within 2%: the noise's own mean moves by about
// 0.5 / sqrt(12288) = 0.45% (three standard errors 1.4%), and the filter is not an unbiased estimator (0.9% here).
// The same input twice gives the same bits.
TEST(OpenImageDenoise, TakesTheNoiseOutOfASmoothImageAndKeepsItsMean) {
  std::string why;
  const auto denoiser = load_or_null(&why);
  if (!denoiser) GTEST_SKIP() << why;
  const int w = 128, h = 96;
  std::vector<float> truth(size_t(w) * h * 3), albedo(truth.size()), normal(truth.size()), noisy(truth.size());
  std::mt19937 rng(59);
  std::normal_distribution<float> noise(1.0f, 0.5f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = 3 * (size_t(y) * w + x);
      const float a = ((x / 16 + y / 16) % 2) ? 0.8f : 0.25f;
      const float light = 0.6f + 0.4f * std::sin(0.05f * x) * std::cos(0.04f * y);
      const float n = std::max(noise(rng), 0.0f);
      for (int c = 0; c < 3; ++c) {
        albedo[i + c] = a;
        truth[i + c] = a * light;
        noisy[i + c] = truth[i + c] * n;
      }
      normal[i + 2] = 1.0f;
    }
  auto squared_error = [&](const std::vector<float>& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.size(); ++i) sum += (double(image[i]) - truth[i]) * (double(image[i]) - truth[i]);
    return sum;
  };
  std::vector<float> denoised = noisy, again = noisy;
  denoiser->denoise(denoised, w, h, {&albedo, &normal});
  denoiser->denoise(again, w, h, {&albedo, &normal});
  const double noisy_error = squared_error(noisy), denoised_error = squared_error(denoised);
  const double mean_ratio = mean_luminance(denoised) / mean_luminance(truth);
  std::printf("%s device: squared error %.4g -> %.4g (%.3fx), mean over the truth %.4f\n",
              denoiser->device_name().c_str(), noisy_error, denoised_error, denoised_error / noisy_error, mean_ratio);
  EXPECT_LT(denoised_error, 0.2 * noisy_error);
  EXPECT_NEAR(mean_ratio, 1.0, 0.02);
  EXPECT_EQ(denoised, again) << "the same input twice gave different bits";
  std::vector<float> wrong_size(10, 0.0f);
  EXPECT_THROW(denoiser->denoise(wrong_size, w, h, {}), Error);
}

// A frame of a room with a sharp glossy floor lit by a point light: the glossy layer is the only one it samples per
// pixel (punctual light: the direct layer is exact and stays). After denoise_frame the noisy layers are the frame's
// as rendered, the cache's part of the indirect light (indirect - glossy) has not moved, the colour is emission +
// direct + indirect again, and the glossy layer's mean stays within 2% of the noisy one's.
TEST(OpenImageDenoise, AFrameComposesTheDenoisedGlossyLayerWithTheCachesLight) {
  std::string why;
  const auto denoiser = load_or_null(&why);
  if (!denoiser) GTEST_SKIP() << why;
  const Scene room = test::caustic_room(0.06f);
  RenderSettings s;
  s.width = 64;
  s.height = 48;
  RenderedImage image = render(test::gpu(), room, s);
  ASSERT_EQ(image.glossy.size(), image.indirect.size()) << "the frame has no glossy layer";
  const RenderedImage before = image;
  denoise_frame(*denoiser, DenoiseChoice{}, image);
  EXPECT_EQ(image.stats.denoise.layers, "glossy");
  EXPECT_EQ(image.noisy_color, before.color);
  EXPECT_EQ(image.noisy_glossy, before.glossy);
  EXPECT_EQ(image.noisy_indirect, before.indirect);
  EXPECT_EQ(image.direct, before.direct);
  EXPECT_NE(image.glossy, before.glossy);
  for (size_t i = 0; i < image.color.size(); ++i) {
    ASSERT_NEAR(image.indirect[i] - image.glossy[i], before.indirect[i] - before.glossy[i],
                1e-5f * (1.0f + before.indirect[i]))
        << "value " << i;
    ASSERT_NEAR(image.color[i], image.emission[i] + image.direct[i] + image.indirect[i], 1e-6f) << "value " << i;
    ASSERT_TRUE(std::isfinite(image.color[i]));
  }
  const double ratio = mean_luminance(image.glossy) / mean_luminance(before.glossy);
  std::printf("glossy layer's mean denoised over noisy: %.4f\n", ratio);
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

// Without the library: an error naming what was tried and how to install it, from the library and from the command
// line (exit 1, no output file).
TEST(Denoise, WithoutTheLibraryTheErrorSaysHowToInstallIt) {
  const char* old = std::getenv("RCSPLAT_OIDN_LIBRARY");
  const std::string saved = old ? old : "";
  setenv("RCSPLAT_OIDN_LIBRARY", "/nonexistent/libOpenImageDenoise.so.2", 1);
  try {
    Denoiser::load();
    ADD_FAILURE() << "a missing library loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/libOpenImageDenoise.so.2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("scripts/install-oidn.sh"), std::string::npos) << e.what();
  }
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "rcsplat_denoise_missing.png";
  std::filesystem::remove(out);
  const std::string command = std::string(RCSPLAT_BINARY) + " render --denoise --width 32 --height 32 -o " +
                              out.string() + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << "status " << status;
  EXPECT_FALSE(std::filesystem::exists(out));
  if (old)
    setenv("RCSPLAT_OIDN_LIBRARY", saved.c_str(), 1);
  else
    unsetenv("RCSPLAT_OIDN_LIBRARY");
}

}  // namespace
}  // namespace rcsplat
