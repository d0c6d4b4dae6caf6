// The glossy pass's samples in rounds (passes/sample_rounds.h, kernels/glossy.cl): where the later rounds go, and
// that the rounds' estimate is the same light as one round of many samples.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pass_probe.h"
#include "cache_test_scenes.h"
#include "corridor_scene.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/glossy_pass.h"
#include "passes/sample_rounds.h"
#include "render/camera.h"
#include "scene/cornell_box.h"
#include "scene/scene_frame.h"

using namespace rcsplat;

namespace {

// An error image: variance `noisy` in the left half, `quiet` in the right, luminance 1, four refined sub-pixels each.
std::vector<cl_float4> two_halves(int width, int height, float noisy, float quiet) {
  std::vector<cl_float4> errors(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) errors[size_t(y) * size_t(width) + size_t(x)] = {{x < width / 2 ? noisy : quiet, 1.0f, 4.0f, 0.5f}};
  return errors;
}

uint64_t chunks_spent(const std::vector<uint8_t>& levels, const std::vector<cl_float4>& errors) {
  uint64_t chunks = 0;
  for (size_t i = 0; i < levels.size(); ++i) chunks += uint64_t(errors[i].s[2]) * ((uint64_t(1) << levels[i]) - 1);
  return chunks;
}

// The mean over the frame of an RGBA image's RGB.
double frame_mean(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
  return sum / double(rgba.size() / 4);
}

// The frame means of several seeds' runs: their mean and its standard error.
std::pair<double, double> mean_and_standard_error(const std::vector<double>& means) {
  const double n = double(means.size());
  double mean = 0.0, variance = 0.0;
  for (double m : means) mean += m / n;
  for (double m : means) variance += (m - mean) * (m - mean) / (n - 1.0);
  return {mean, std::sqrt(variance / n)};
}

}  // namespace

// The doublings go to the noisy half first, spend at most the budget and most of it, and give the same levels twice;
// with no error anywhere there is nothing to refine.
TEST(SampleRounds, DoublingsGoWhereTheErrorIsWithinTheBudget) {
  const int w = 32, h = 16;
  const std::vector<cl_float4> errors = two_halves(w, h, 1.0f, 1e-3f);
  const double extra = 1.5 * 4.0 * double(w * h);  // 1.5 chunks more a sub-pixel on average
  const std::vector<uint8_t> levels = refinement_levels(errors, w, h, extra);
  const uint64_t spent = chunks_spent(levels, errors);
  EXPECT_LE(double(spent), extra);
  EXPECT_GE(double(spent), 0.5 * extra) << "most of the budget should be spent";
  unsigned least_noisy = kRoundsMaxLevel, most_quiet = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned level = levels[size_t(y) * w + size_t(x)];
      if (x < w / 2 - 1) least_noisy = std::min(least_noisy, level);  // away from the neighbourhoods that mix halves
      if (x > w / 2) most_quiet = std::max(most_quiet, level);
    }
  EXPECT_GT(least_noisy, most_quiet) << "the noisy half should take more doublings than the quiet one";
  EXPECT_EQ(refinement_levels(errors, w, h, extra), levels);
  const std::vector<uint8_t> none = refinement_levels(two_halves(w, h, 0.0f, 0.0f), w, h, extra);
  EXPECT_EQ(chunks_spent(none, errors), 0u);
  EXPECT_EQ(chunks_spent(refinement_levels(errors, w, h, 0.0), errors), 0u) << "no budget, no doublings";
}

// The corridor with metal walls of roughness 0.3 (sampled per pixel, LOBE_GLOSSY) and its bright spot: the glossy
// light in rounds (a budget of 8 lobe samples a pixel: one chunk of 2 each, then doublings by estimated error) over 8
// seeds, against one round of 512 a pixel. Each pixel's samples stay unbiased whatever count its rounds give it, so the
// frame's mean over the seeds is within four standard errors (the seeds' spread) of the converged one's; and the
// rounds spend at most the budget.
TEST(GlossyKernel, RoundsByEstimatedErrorKeepTheLightsMean) {
  const Scene corridor = test::bright_patch_corridor(0.3f);
  test::TwinScene twin(SceneFrame::fitted(corridor).device_scene(corridor));
  GpuContext& gpu = test::gpu();
  const int w = 48, h = 36;
  GBufferPass gbuffer(gpu, twin.device);
  gbuffer.run(camera_params(choose_camera(twin.scene, 0, {}), w, h));
  GlossyPass glossy(gpu, twin.device, false);
  glossy.run(gbuffer.view(), 512, 1000, {}, 0, 0, 1, {}, {}, false);
  const double converged = frame_mean(test::PassProbe::glossy_rgba(glossy));
  ASSERT_GT(converged, 0.0) << "the walls should reflect the bright spot";
  const int seeds = 8, budget = 8;
  std::vector<double> means;
  for (int seed = 0; seed < seeds; ++seed) {
    const GlossyRunStats stats = glossy.run(gbuffer.view(), budget, unsigned(seed), {}, 0, 0, 1, {}, {}, true);
    ASSERT_GT(stats.sampled_sub_pixels, 100u);
    EXPECT_GT(stats.rounds, 1u) << "the budget leaves room for later rounds";
    EXPECT_LE(double(stats.chunks), double(budget) / GLOSSY_CHUNK_LOBE * double(stats.sampled_sub_pixels));
    means.push_back(frame_mean(test::PassProbe::glossy_rgba(glossy)));
  }
  const auto [mean, standard_error] = mean_and_standard_error(means);
  std::printf("glossy light's frame mean: rounds %.5f +- %.5f over %d seeds, one round of 512 %.5f\n", mean,
              standard_error, seeds, converged);
  EXPECT_LT(std::abs(mean - converged), 4.0 * standard_error + 1e-3 * converged);
}

// The built-in Cornell box's direct light from its ceiling light in rounds (a budget of 16 samples a pixel: four each
// first, then doublings where the neighbours' samples estimate the most error), over 8 seeds, against one pass of
// 32 x 32 strata: the frame's mean within four standard errors.
TEST(DirectLight, RoundsByEstimatedErrorKeepTheLightsMean) {
  test::TwinScene twin(make_cornell_box());
  GpuContext& gpu = test::gpu();
  const int w = 48, h = 48;
  GBufferPass gbuffer(gpu, twin.device);
  gbuffer.run(camera_params(choose_camera(twin.scene, 0, {}), w, h));
  DirectPass direct(gpu, twin.device);
  direct.run(gbuffer.view(), 32, 1000);
  const double converged = frame_mean(gpu.download<float>(direct.radiance(), size_t(w * h) * 4));
  ASSERT_GT(converged, 0.0);
  std::vector<double> means;
  for (unsigned seed = 0; seed < 8; ++seed) {
    const DirectRunStats stats = direct.run(gbuffer.view(), 4, seed, 16);
    ASSERT_GT(stats.rounds, 1u);
    EXPECT_LE(double(stats.samples), 16.0 * double(stats.sampled_sub_pixels));
    EXPECT_GT(stats.refined_pixels, 0u);
    means.push_back(frame_mean(gpu.download<float>(direct.radiance(), size_t(w * h) * 4)));
  }
  const auto [mean, standard_error] = mean_and_standard_error(means);
  std::printf("direct light's frame mean: rounds %.6f +- %.6f over 8 seeds, 32 x 32 strata %.6f\n", mean,
              standard_error, converged);
  EXPECT_LT(std::abs(mean - converged), 4.0 * standard_error + 1e-4 * converged);
}
