// The layers gathered at output resolution (kernels/layers.cl, passes/layer_pass.h): on random sub-pixel images, each
// output pixel's means, sums, centre sub-pixel and counts against a double-precision reference written here, for
// sub-pixel grids of 1 x 1 (a copy), 2 x 2 and 3 x 3 (odd: the centre is the middle one).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "passes/layer_pass.h"
#include "render/placement.h"
#include "render/renderer.h"
#include "lobed_cornell_box.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

// A float sum of at most 9 values in [0, 1] is off from the exact one by at most 9 * 9 * 2^-24 (each addition's
// rounding, bounded by the sum so far): under 5e-6 for the sum, 1e-6 for the mean. Counts are whole numbers, exact.
constexpr double kMeanTolerance = 1e-6;

struct SubPixelFrame {
  unsigned side;
  int out_width, out_height;
  int width() const { return out_width * int(side); }
  int height() const { return out_height * int(side); }
  size_t sub_pixel(int x, int y, unsigned i, unsigned j) const {
    return (size_t(y) * side + j) * size_t(width()) + size_t(x) * side + i;
  }
};

std::vector<GBufferSample> random_gbuffer(size_t count, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> triangle(-1, 5), lobe(LOBE_NONE, LOBE_HSH);
  std::vector<GBufferSample> g(count);
  for (GBufferSample& s : g) {
    for (int c = 0; c < 3; ++c) {
      s.position[c] = unit(rng);
      s.normal[c] = unit(rng);
      s.albedo[c] = unit(rng);
      s.emission[c] = unit(rng);
    }
    s.depth = unit(rng);
    s.triangle = triangle(rng);
    s.lobe = lobe(rng);
    // Half the samples carry a normal map's normal: any point of the octahedral square encodes one.
    s.mapped_normal[0] = unit(rng) < 0.5f ? NO_MAPPED_NORMAL : 2.0f * unit(rng) - 1.0f;
    s.mapped_normal[1] = 2.0f * unit(rng) - 1.0f;
  }
  return g;
}

// The normal a sample shades with, in double: its octahedral-encoded mapped normal (the square's outer triangles fold
// onto the lower hemisphere), else the interpolated one.
glm::dvec3 shading_normal(const GBufferSample& s) {
  if (s.mapped_normal[0] == NO_MAPPED_NORMAL) return glm::dvec3(s.normal[0], s.normal[1], s.normal[2]);
  const double x = s.mapped_normal[0], y = s.mapped_normal[1], z = 1.0 - std::fabs(x) - std::fabs(y);
  glm::dvec3 n(x, y, z);
  if (z < 0.0) n = glm::dvec3((1.0 - std::fabs(y)) * (x >= 0.0 ? 1.0 : -1.0), (1.0 - std::fabs(x)) * (y >= 0.0 ? 1.0 : -1.0), z);
  return glm::normalize(n);
}

std::vector<cl_float4> random_rgba(size_t count, std::mt19937& rng, bool whole_alpha) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<cl_float4> v(count);
  for (cl_float4& p : v) {
    for (int c = 0; c < 4; ++c) p.s[c] = unit(rng);
    if (whole_alpha) p.s[3] = std::floor(p.s[3] * 40.0f);  // a ray count
  }
  return v;
}

// An irradiance image (RGB, the weight in A) in which about a third of the sub-pixels no record reached (weight 0).
std::vector<cl_float4> random_irradiance_with_holes(size_t count, std::mt19937& rng) {
  std::vector<cl_float4> irradiance = random_rgba(count, rng, false);
  std::uniform_int_distribution<int> coin(0, 2);
  for (cl_float4& e : irradiance)
    if (coin(rng) == 0) e.s[3] = 0.0f;
  return irradiance;
}

GBufferView view_of(GpuContext& gpu, const std::vector<GBufferSample>& g, const SubPixelFrame& f) {
  GBufferView view;
  view.samples = gpu.upload(g);
  view.width = f.width();
  view.height = f.height();
  return view;
}

class LayerPassTest : public ::testing::TestWithParam<unsigned> {};

TEST_P(LayerPassTest, SurfaceIsTheSubPixelsMeansCentreAndCounts) {
  GpuContext& gpu = test::gpu();
  const SubPixelFrame f{GetParam(), 13, 7};
  std::mt19937 rng(17 + f.side);
  const std::vector<GBufferSample> g = random_gbuffer(size_t(f.width()) * f.height(), rng);
  const std::vector<cl_float4> direct = random_rgba(g.size(), rng, true);
  LayerPass layers(gpu, f.side, f.out_width, f.out_height);
  layers.set_piece_pixels(7);  // pieces of 7 pixels, the last one short: the frame comes down in several
  const std::vector<PixelSurface> out = layers.surface(view_of(gpu, g, f), gpu.upload(direct));
  ASSERT_EQ(out.size(), size_t(f.out_width) * f.out_height);
  const double n = double(f.side * f.side);
  for (int y = 0; y < f.out_height; ++y)
    for (int x = 0; x < f.out_width; ++x) {
      const PixelSurface& s = out[size_t(y) * f.out_width + x];
      double emission[3] = {}, light[3] = {}, albedo[3] = {}, normal[3] = {}, shadow_rays = 0;
      unsigned by_lobe[4] = {};
      for (unsigned j = 0; j < f.side; ++j)
        for (unsigned i = 0; i < f.side; ++i) {
          const size_t k = f.sub_pixel(x, y, i, j);
          for (int c = 0; c < 3; ++c) {
            emission[c] += g[k].emission[c];
            light[c] += direct[k].s[c];
            albedo[c] += g[k].albedo[c];
            normal[c] += shading_normal(g[k])[c];
          }
          shadow_rays += direct[k].s[3];
          if (g[k].triangle >= 0) ++by_lobe[g[k].lobe];
        }
      const GBufferSample& centre = g[f.sub_pixel(x, y, f.side / 2, f.side / 2)];
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(s.emission[c], emission[c] / n, kMeanTolerance) << x << "," << y;
        EXPECT_NEAR(s.direct[c], light[c] / n, kMeanTolerance) << x << "," << y;
        EXPECT_NEAR(s.albedo[c], albedo[c] / n, kMeanTolerance) << x << "," << y;
        EXPECT_NEAR(s.normal[c], normal[c] / n, kMeanTolerance) << x << "," << y;
        EXPECT_EQ(s.position[c], centre.position[c]) << x << "," << y;
      }
      EXPECT_EQ(s.depth, centre.depth);
      EXPECT_EQ(s.triangle, centre.triangle);
      EXPECT_EQ(double(s.shadow_rays), shadow_rays);
      EXPECT_EQ(s.lobe_counts & 0xffu, by_lobe[LOBE_ROUGH]) << x << "," << y;
      EXPECT_EQ((s.lobe_counts >> 8) & 0xffu, by_lobe[LOBE_GLOSSY]) << x << "," << y;
      EXPECT_EQ((s.lobe_counts >> 16) & 0xffu, by_lobe[LOBE_HSH]) << x << "," << y;
      EXPECT_EQ(s.lobe_counts >> 24, 0u);
    }
}

TEST_P(LayerPassTest, ImagesAreTheSubPixelsMean) {
  GpuContext& gpu = test::gpu();
  const SubPixelFrame f{GetParam(), 11, 9};
  std::mt19937 rng(29 + f.side);
  const std::vector<cl_float4> image = random_rgba(size_t(f.width()) * f.height(), rng, false);
  LayerPass layers(gpu, f.side, f.out_width, f.out_height);
  layers.set_piece_pixels(7);  // pieces of 7 pixels, the last one short: the frame comes down in several
  const cl::Buffer buffer = gpu.upload(image);
  const std::vector<float> mean = layers.mean_rgba(buffer);
  const double n = double(f.side * f.side);
  for (int y = 0; y < f.out_height; ++y)
    for (int x = 0; x < f.out_width; ++x)
      for (int c = 0; c < 4; ++c) {
        double expected = 0;
        for (unsigned j = 0; j < f.side; ++j)
          for (unsigned i = 0; i < f.side; ++i) expected += image[f.sub_pixel(x, y, i, j)].s[c];
        const size_t o = (size_t(y) * f.out_width + x) * 4 + c;
        EXPECT_NEAR(mean[o], expected / n, kMeanTolerance) << x << "," << y << " channel " << c;
      }
}

TEST_P(LayerPassTest, RecordCountsAreReachingMeanSittingAndUncovered) {
  GpuContext& gpu = test::gpu();
  const SubPixelFrame f{GetParam(), 10, 6};
  std::mt19937 rng(41 + f.side);
  const size_t count = size_t(f.width()) * f.height();
  const std::vector<GBufferSample> g = random_gbuffer(count, rng);
  const std::vector<cl_float4> irradiance = random_irradiance_with_holes(count, rng);
  std::vector<cl_uint> reaching(count);
  std::vector<cl_int> sitting(count);
  std::uniform_int_distribution<int> few(0, 20), coin(0, 2);
  for (size_t k = 0; k < count; ++k) {
    reaching[k] = cl_uint(few(rng));
    sitting[k] = coin(rng) == 0 ? few(rng) : -1;
  }
  LayerPass layers(gpu, f.side, f.out_width, f.out_height);
  layers.set_piece_pixels(7);  // pieces of 7 pixels, the last one short: the frame comes down in several
  const std::vector<float> out = layers.record_counts(view_of(gpu, g, f), gpu.upload(irradiance), gpu.upload(reaching),
                                                      gpu.upload(sitting));
  const double n = double(f.side * f.side);
  for (int y = 0; y < f.out_height; ++y)
    for (int x = 0; x < f.out_width; ++x) {
      double reach = 0, sit = 0, uncovered = 0;
      for (unsigned j = 0; j < f.side; ++j)
        for (unsigned i = 0; i < f.side; ++i) {
          const size_t k = f.sub_pixel(x, y, i, j);
          reach += reaching[k];
          sit += sitting[k] >= 0;
          uncovered += g[k].triangle >= 0 && irradiance[k].s[3] == 0.0f;
        }
      const float* o = &out[(size_t(y) * f.out_width + x) * 4];
      EXPECT_NEAR(o[0], reach / n, 1e-6 * reach / n) << x << "," << y;
      EXPECT_EQ(double(o[1]), sit) << x << "," << y;
      EXPECT_EQ(double(o[2]), uncovered) << x << "," << y;
      EXPECT_EQ(o[3], 0.0f);
    }
}

// The counts a colour-only frame sums on the device (RenderSettings::color_only) against the host's sums over the same
// random sub-pixels: whole numbers, so equal.
TEST_P(LayerPassTest, DeviceCountsAreTheSubPixelsSums) {
  GpuContext& gpu = test::gpu();
  const SubPixelFrame f{GetParam(), 17, 11};
  std::mt19937 rng(53 + f.side);
  const size_t count = size_t(f.width()) * f.height();
  const std::vector<GBufferSample> g = random_gbuffer(count, rng);
  const std::vector<cl_float4> rays = random_rgba(count, rng, true);
  const std::vector<cl_float4> irradiance = random_irradiance_with_holes(count, rng);
  uint64_t by_lobe[LOBE_KINDS] = {}, ray_sum = 0, uncovered = 0;
  for (size_t k = 0; k < count; ++k) {
    if (g[k].triangle >= 0 && g[k].lobe != LOBE_NONE) ++by_lobe[g[k].lobe];
    ray_sum += uint64_t(rays[k].s[3]);
    uncovered += g[k].triangle >= 0 && irradiance[k].s[3] == 0.0f;
  }
  LayerPass layers(gpu, f.side, f.out_width, f.out_height);
  const GBufferView view = view_of(gpu, g, f);
  const std::array<uint64_t, LOBE_KINDS> lobes = layers.count_lobes(view);
  for (int lobe = 0; lobe < LOBE_KINDS; ++lobe) EXPECT_EQ(lobes[size_t(lobe)], by_lobe[lobe]) << "lobe " << lobe;
  EXPECT_GT(by_lobe[LOBE_HSH], 0u);
  EXPECT_EQ(layers.sum_alpha(view, gpu.upload(rays)), ray_sum);
  EXPECT_EQ(layers.count_uncovered(view, gpu.upload(irradiance)), uncovered);
}

// The clamped reaches a colour-only frame counts on the device (its records stay there) against the count made by
// construction: random records, a third at the lower clamp (radius = min_reach / accuracy pixels, as reduce_records
// clamps it), a third at the upper, a third strictly between; and against the host's count_clamped_radii, which the
// summary of a full frame uses. Whole numbers: equal. Several work-groups and a partial last one.
TEST(LayerPass, DeviceCountsTheRecordsAtEachReachClamp) {
  GpuContext& gpu = test::gpu();
  CacheSettings cache;
  std::mt19937 rng(71);
  std::uniform_real_distribution<float> size(1e-3f, 1.0f), between(1.01f, 0.99f * cache.max_reach_pixels /
                                                                                   cache.min_reach_pixels);
  std::vector<CacheRecord> records(3 * LAYER_COUNT_GROUP + 37);
  uint64_t at_min = 0, at_max = 0;
  for (size_t k = 0; k < records.size(); ++k) {
    CacheRecord& r = records[k];
    r = CacheRecord{};
    r.pixel_size = size(rng);
    const float min_radius_pixels = cache.min_reach_pixels / cache.accuracy;
    const float max_radius_pixels = cache.max_reach_pixels / cache.accuracy;
    switch (k % 3) {
      case 0: r.radius = min_radius_pixels * r.pixel_size; ++at_min; break;
      case 1: r.radius = max_radius_pixels * r.pixel_size; ++at_max; break;
      default: r.radius = between(rng) * min_radius_pixels * r.pixel_size; break;
    }
  }
  RecordStats host;
  count_clamped_radii(records, cache, host);
  EXPECT_EQ(host.at_min_radius, at_min);
  EXPECT_EQ(host.at_max_radius, at_max);
  LayerPass layers(gpu, 1, 4, 4);
  const cl::Buffer on_device = gpu.upload(records);
  const std::array<uint64_t, 2> counted = layers.count_clamped_reaches(on_device, uint32_t(records.size()), cache);
  EXPECT_EQ(counted[0], at_min);
  EXPECT_EQ(counted[1], at_max);
  // The first records only: the launch stops at the count.
  const std::array<uint64_t, 2> first = layers.count_clamped_reaches(on_device, 5, cache);
  EXPECT_EQ(first[0], 2u);
  EXPECT_EQ(first[1], 2u);
}

INSTANTIATE_TEST_SUITE_P(SubPixelSides, LayerPassTest, ::testing::Values(1u, 2u, 3u));

// A frame that asks for its colour alone (PNG outputs, walkthrough frames) gets the same colour, bit for bit, and the
// same summary counts, with no other layer and no record brought back from the device. The lobed Cornell box at 2 x 2 sub-pixels:
// rough, glossy and radiance-cached pixels, the glossy pass's rays, the light guide's share.
TEST(LayerPass, AColourOnlyFrameIsTheFullFramesColourWithNoOtherLayer) {
  const Scene scene = test::cornell_box_with_lobes(0.1f, 0.5f);
  RenderSettings s = test::one_bounce_one_sample();
  s.width = s.height = 40;
  s.pixel_samples = 4;
  s.light_samples = 4;
  s.bounces = 2;
  s.bounce_method = BounceMethod::photons;
  s.photon_paths = 1u << 14;
  s.caustic_photons = 1u << 14;
  const RenderedImage full = render(test::gpu(), scene, s);
  s.color_only = true;
  const RenderedImage colour = render(test::gpu(), scene, s);
  EXPECT_EQ(colour.color, full.color);
  for (const std::vector<float>* layer : {&colour.direct, &colour.emission, &colour.albedo, &colour.normal,
                                          &colour.position, &colour.depth, &colour.indirect, &colour.irradiance,
                                          &colour.coverage, &colour.records_per_pixel, &colour.record_positions})
    EXPECT_TRUE(layer->empty());
  EXPECT_TRUE(colour.triangle.empty());
  EXPECT_TRUE(colour.records.empty()) << "the glossy pass reads the records where they are";
  const RenderStats &a = colour.stats, &b = full.stats;
  EXPECT_TRUE(a.glossy.reads_records);
  EXPECT_EQ(a.irradiance.at_min_radius, b.irradiance.at_min_radius);
  EXPECT_EQ(a.irradiance.at_max_radius, b.irradiance.at_max_radius);
  EXPECT_GT(b.primary.rough_pixels, 0u);
  EXPECT_GT(b.primary.glossy_pixels, 0u);
  EXPECT_GT(b.primary.hsh_pixels, 0u);
  EXPECT_GT(b.glossy.rays, 0u);
  EXPECT_EQ(a.primary.rough_pixels, b.primary.rough_pixels);
  EXPECT_EQ(a.primary.glossy_pixels, b.primary.glossy_pixels);
  EXPECT_EQ(a.primary.hsh_pixels, b.primary.hsh_pixels);
  EXPECT_EQ(a.primary.shadow_rays, b.primary.shadow_rays);
  EXPECT_EQ(a.primary.primary_rays, b.primary.primary_rays);
  EXPECT_EQ(a.glossy.rays, b.glossy.rays);
  EXPECT_EQ(a.irradiance.uncovered_pixels, b.irradiance.uncovered_pixels);
}

// Direct light alone and path tracing (one frame, and rounds over the pixels' area) ask for their colour alone too:
// the same colour, bit for bit, and the same counts, with no surface layer brought back. Planted once: the device's
// colour without the emission failed the bits in all three.
TEST(LayerPass, ColourOnlyFramesOfDirectLightAndPathTracingAreTheFullFramesColour) {
  const Scene scene = test::cornell_box_with_lobes(0.1f, 0.5f);
  for (const GiMethod gi : {GiMethod::none, GiMethod::path}) {
    for (const bool pixel_area : {false, true}) {
      if (pixel_area && gi != GiMethod::path) continue;
      RenderSettings s = test::one_bounce_one_sample();
      s.width = s.height = 24;
      s.pixel_samples = 9;
      s.light_samples = 4;
      s.gi = gi;
      s.path.samples = 9;  // a multiple of the pixel samples
      s.path.pixel_area = pixel_area;
      const RenderedImage full = render(test::gpu(), scene, s);
      s.color_only = true;
      const RenderedImage colour = render(test::gpu(), scene, s);
      const std::string what = std::string(gi == GiMethod::none ? "direct light" : "path tracing") +
                               (pixel_area ? " over the pixels' area" : "");
      EXPECT_EQ(colour.color, full.color) << what;
      for (const std::vector<float>* layer :
           {&colour.direct, &colour.emission, &colour.albedo, &colour.normal, &colour.position, &colour.depth})
        EXPECT_TRUE(layer->empty()) << what;
      EXPECT_TRUE(colour.triangle.empty()) << what;
      EXPECT_FALSE(full.direct.empty()) << what;
      const RenderStats &a = colour.stats, &b = full.stats;
      EXPECT_GT(b.primary.glossy_pixels, 0u) << what;
      EXPECT_EQ(a.primary.rough_pixels, b.primary.rough_pixels) << what;
      EXPECT_EQ(a.primary.glossy_pixels, b.primary.glossy_pixels) << what;
      EXPECT_EQ(a.primary.hsh_pixels, b.primary.hsh_pixels) << what;
      EXPECT_EQ(a.primary.shadow_rays, b.primary.shadow_rays) << what;
      EXPECT_EQ(a.path.rays, b.path.rays) << what;
    }
  }
}

TEST(LayerPass, AGBufferOfAnotherSizeIsRefused) {
  GpuContext& gpu = test::gpu();
  LayerPass layers(gpu, 2, 8, 8);
  GBufferView view;
  view.samples = gpu.buffer(CL_MEM_READ_ONLY, 15 * 16 * sizeof(GBufferSample), "test");
  view.width = 15;
  view.height = 16;
  EXPECT_THROW(layers.surface(view, gpu.buffer(CL_MEM_READ_ONLY, 15 * 16 * 16, "test")), Error);
}

}  // namespace
}  // namespace rcsplat
