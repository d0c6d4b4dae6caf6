// Hard cases for an irradiance cache (issue 10), on scenes the tests build themselves: the same scene far from the
// origin or at another scale, a small very bright indirect source, ...
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <thread>

#include "image/error_metrics.h"
#include "kernels/hsh.h"
#include "image/exr_file.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "scene/scene_frame.h"
#include "cache_test_scenes.h"
#include "test_support.h"
#include "util/error.h"
#include "util/host_heap.h"

namespace rcsplat {
namespace {

// The scene moved to offset + scale * p: SceneFrame's change of units read the other way (a frame centred at
// -offset / scale, of scale 1 / scale). Point and spot intensities scale with the square of the length so that
// irradiance, and so every pixel, stays the same; radiance (emission) does not change.
Scene moved_and_scaled(const Scene& s, glm::dvec3 offset, double scale) {
  return SceneFrame{-offset / scale, 1.0 / scale}.device_scene(s);
}

TEST(HardCases, SceneFarFromTheOriginOrRescaledRendersTheSame) {
  const Scene original = moved_and_scaled(make_cornell_box(), glm::dvec3(0.0), 1.0 / 555.0);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 64;
  settings.light_samples = 4;
  settings.seed = 1;
  RenderedImage base = render(test::gpu(), original, settings);
  settings.seed = 2;
  RenderedImage other_seed = render(test::gpu(), original, settings);
  const double seed_noise_indirect = image_error(other_seed.indirect, base.indirect).rel_mse;
  const double seed_noise_direct = image_error(other_seed.direct, base.direct).rel_mse;
  std::printf("two seeds: indirect %.3e direct %.3e, records %llu / %llu\n", seed_noise_indirect, seed_noise_direct,
              (unsigned long long)base.stats.irradiance.records,
              (unsigned long long)other_seed.stats.irradiance.records);
  settings.seed = 1;
  struct Case { const char* name; glm::dvec3 offset; double scale; };
  const Case cases[] = {{"offset 1e5", glm::dvec3(1e5, -1e5, 1e5), 1.0},
                        {"scale 1e-3", glm::dvec3(0.0), 1e-3},
                        {"scale 1e4", glm::dvec3(0.0), 1e4}};
  for (const Case& c : cases) {
    // Single precision rounds the moved vertices (at 1e5, to 1/128 of this unit box): the scene to match is that
    // rounded geometry brought back exactly, in double precision.
    const Scene moved = moved_and_scaled(original, c.offset, c.scale);
    RenderedImage img = render(test::gpu(), moved, settings);
    RenderedImage back = render(test::gpu(), moved_and_scaled(moved, -c.offset / c.scale, 1.0 / c.scale), settings);
    double indirect = image_error(img.indirect, back.indirect).rel_mse;
    double direct = image_error(img.direct, back.direct).rel_mse;
    std::printf("%s: indirect %.3e direct %.3e, records %llu\n", c.name, indirect, direct,
                (unsigned long long)img.stats.irradiance.records);
    EXPECT_LT(indirect, seed_noise_indirect) << c.name;
    EXPECT_LT(direct, seed_noise_direct + 1e-6) << c.name;
    EXPECT_NEAR(double(img.stats.irradiance.records), double(base.stats.irradiance.records),
                0.1 * double(base.stats.irradiance.records))
        << c.name;
  }
}

// Issue 10 part 2: records must not turn a small, very bright indirect source into blotches. Block means (8 x 8)
// average noise out and keep blotches. Against the exact indirect light (quadrature, tests/corridor_scene.h) the
// cache's block relMSE must be no worse than stratified path tracing's with as many rays (the deterministic stand-in
// for equal time; benchmarks/RESULTS.md has the timed comparison), and far below the cache's without the light
// guide. A long path-traced run checks the quadrature: its block error must be what its own variance predicts.
// With metal_wall_roughness > 0 the walls and ceiling are glossy metal. At roughness 0.6 (LOBE_HSH) the disc's glossy
// reflection is held by HSH records, and a record whose strata found the disc stamped that reflection over its whole
// footprint; the records now cache only their strata's balance-heuristic share beside the guide, and each pixel
// samples the guide's share itself (kernels/glossy.cl guide_share). At roughness 0.3 (LOBE_GLOSSY) each pixel samples
// its own lobe, and the disc appeared as fireflies; pixels now add half as many samples again aimed at the guide's
// cones (kernels/glossy.cl). Rays counted: records', radiance records' and glossy samples'.
struct CorridorErrors {
  double guided, unguided, path;
};

CorridorErrors corridor_block_errors(float metal_wall_roughness, bool check_reference) {
  const Scene corridor = test::bright_patch_corridor(metal_wall_roughness);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = 64;
  settings.height = 48;
  settings.light_samples = 1;
  settings.seed = 7;
  // Every glossy pixel the same count, so that the guide is measured alone: rounds by estimated error (the default)
  // took the unguided frame's block error from 13 to 1.55 at seed 7, the guided one 0.13 (docs/NOTES.md, 2026-12-06).
  settings.glossy_adaptive = false;
  const RenderedImage guided = render(test::gpu(), corridor, settings);
  const bool glossy = metal_wall_roughness > 0.0f, cached = metal_wall_roughness >= HSH_MIN_ROUGHNESS;
  EXPECT_EQ(guided.stats.radiance.records > 0, cached) << "which walls are radiance-cached";
  EXPECT_EQ(guided.stats.primary.glossy_pixels > 0, glossy && !cached) << "which walls are sampled per pixel";
  const std::vector<float> exact = test::corridor_indirect_by_quadrature(corridor, guided);
  auto block_error = [&](const RenderedImage& img) {
    for (float v : img.indirect) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
    return block_rel_mse(img.indirect, exact, settings.width, settings.height, 8);
  };
  RenderSettings unguided_settings = settings;
  unguided_settings.cache.guide_rays = 0;
  const RenderedImage unguided = render(test::gpu(), corridor, unguided_settings);
  // Stratified path tracing with at least the cache's rays (both share the G-buffer and direct light).
  RenderSettings path_settings = settings;
  path_settings.gi = GiMethod::path;
  path_settings.path.stratified = true;
  path_settings.path.pixel_area = false;  // the quadrature's points, the pixels' centres
  path_settings.path.samples = 1;
  const double rays_per_sample = double(render(test::gpu(), corridor, path_settings).stats.path.rays);
  const double cache_rays =
      double(guided.stats.irradiance.rays + guided.stats.radiance.rays + guided.stats.glossy.rays);
  unsigned side = unsigned(std::ceil(std::sqrt(cache_rays / rays_per_sample)));
  path_settings.path.samples = side * side;
  const RenderedImage path = render(test::gpu(), corridor, path_settings);
  CorridorErrors e{block_error(guided), block_error(unguided), block_error(path)};
  std::printf("metal walls of roughness %.2f (0: grey Lambertian), 8x8 block relMSE against the quadrature: guided "
              "cache %.3e (%.0f rays), without the guide %.3e, stratified path tracing %.3e (%u spp)\n",
              metal_wall_roughness, e.guided, cache_rays, e.unguided, e.path, path_settings.path.samples);
  if (check_reference) {
    RenderSettings long_path_settings = settings;
    long_path_settings.gi = GiMethod::path;
    long_path_settings.path.samples = 2048;
    long_path_settings.path.pixel_area = false;
    const RenderedImage long_path = render(test::gpu(), corridor, long_path_settings);
    const double noise = block_rel_mse_of_noise(long_path.indirect_variance, exact, settings.width, settings.height, 8);
    std::printf("2048 spp %.3e, its variance predicts %.3e\n", block_error(long_path), noise);
    EXPECT_NEAR(block_error(long_path), noise, 0.5 * noise) << "the quadrature is not the reference";
  }
  return e;
}

TEST(HardCases, SmallBrightIndirectSourceLeavesNoBlotches) {
  CorridorErrors e = corridor_block_errors(0.0f, true);
  EXPECT_LE(e.guided, e.path);
  EXPECT_LT(e.guided, 0.05 * e.unguided);
}

// The quadrature with the BRDF is checked here. With the guided rays projected into the records' HSH (a first
// version) the block error was 0.16 against the unguided 4.4: the truncated basis rang against the bright disc; with
// the pixels sampling the guide's share, 0.019.
TEST(HardCases, SmallBrightIndirectSourceOnRadianceCachedWalls) {
  CorridorErrors e = corridor_block_errors(0.6f, true);
  EXPECT_LE(e.guided, e.path);
  EXPECT_LT(e.guided, 0.02 * e.unguided);
}

TEST(HardCases, SmallBrightIndirectSourceOnSampledGlossyWalls) {
  CorridorErrors e = corridor_block_errors(0.3f, false);
  EXPECT_LE(e.guided, e.path);
  // Seeds 7 to 15 gave 0.04 to 0.2 against the unguided 13: what is left is at the walls' foot beside the disc, inside
  // the cluster's sphere, where no cone can be aimed and the lobe's samples find the disc alone. Since the samples
  // come in chunks with nested strata (2026-12-06) the unguided frame is 0.63 at seed 7 and the guided 0.045.
  EXPECT_LT(e.guided, 0.1 * e.unguided);
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Same scene, options and device: the same bytes in every output file, however much time passes between the runs
// (OpenImageIO would stamp the clock into the EXR header); SOURCE_DATE_EPOCH, when set, dates it instead.
TEST(Determinism, OutputFilesAreTheSameBytesAcrossRuns) {
  const std::string dir = test::scratch_dir();
  auto run = [&](const std::string& name) {
    const test::CommandRun r =
        test::run_rcsplat(dir, {"render", "--width", "40", "--height", "40", "-o", name + ".exr", "-o", name + ".png"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  };
  unsetenv("SOURCE_DATE_EPOCH");
  run("first");
  // Into the next second, so that a clock time in the header would differ.
  auto now = std::chrono::system_clock::now().time_since_epoch();
  std::this_thread::sleep_for(std::chrono::seconds(1) - (now % std::chrono::seconds(1)) +
                              std::chrono::milliseconds(20));
  run("second");
  for (const char* ext : {".exr", ".png"}) {
    std::string a = file_bytes(dir + "/first" + ext), b = file_bytes(dir + "/second" + ext);
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << ext << " files differ";
  }
  setenv("SOURCE_DATE_EPOCH", "86400", 1);
  run("dated");
  unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(read_exr_header(dir + "/dated.exr").text["DateTime"], "1970:01:02 00:00:00");
}

// The CLI keeps freed host memory for the next allocation (util/host_heap.h), so on a CPU device a frame's buffers are
// often the memory of the frame before, not fresh zero pages: a kernel that read a buffer before writing it would show
// that frame's values. A second frame in the same process must be the same bits as the first.
TEST(Determinism, AFrameOnTheLastFramesMemoryIsTheSameBits) {
  keep_freed_host_memory();
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = 96;
  settings.height = 72;
  const Scene scene = make_cornell_box();
  const RenderedImage first = render(test::gpu(), scene, settings);
  const RenderedImage second = render(test::gpu(), scene, settings);
  ASSERT_FALSE(first.color.empty());
  EXPECT_TRUE(first.color == second.color);
  EXPECT_TRUE(first.irradiance == second.irradiance);
  EXPECT_TRUE(first.records_per_pixel == second.records_per_pixel);
}

// The image layers come down from the device in pieces (passes/layer_pass.h): pieces of 13 pixels, the last one short,
// must fill every layer with the same bits as one piece.
TEST(Determinism, LayersInSmallPiecesAreTheSameBits) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = 40;
  settings.height = 30;
  settings.pixel_samples = 4;
  const Scene scene = make_cornell_box();
  const RenderedImage whole = render(test::gpu(), scene, settings);
  settings.layer_piece_pixels = 13;
  const RenderedImage pieces = render(test::gpu(), scene, settings);
  ASSERT_FALSE(whole.color.empty());
  for (auto layer : {&RenderedImage::color, &RenderedImage::direct, &RenderedImage::emission, &RenderedImage::albedo,
                     &RenderedImage::normal, &RenderedImage::position, &RenderedImage::depth, &RenderedImage::indirect,
                     &RenderedImage::irradiance, &RenderedImage::coverage, &RenderedImage::records_per_pixel,
                     &RenderedImage::record_positions})
    EXPECT_TRUE(whole.*layer == pieces.*layer);
  EXPECT_TRUE(whole.triangle == pieces.triangle);
  EXPECT_EQ(whole.stats.primary.shadow_rays, pieces.stats.primary.shadow_rays);
  EXPECT_EQ(whole.stats.irradiance.uncovered_pixels, pieces.stats.irradiance.uncovered_pixels);
}

// A buffer larger than the device can hold is refused with the words "out of device memory", what it was for and the
// size asked for, before OpenCL is asked.
TEST(DeviceMemory, RefusalNamesWhatAndTheSizeAskedFor) {
  GpuContext& gpu = test::gpu();
  const uint64_t too_big = gpu.device_info().max_allocation + (uint64_t(1) << 30);
  try {
    gpu.buffer(CL_MEM_READ_WRITE, size_t(too_big), "test buffer");
    ADD_FAILURE() << "a buffer of " << too_big << " bytes was allocated";
  } catch (const Error& e) {
    std::string message = e.what();
    char size[32];
    std::snprintf(size, sizeof size, "%.1f MiB", double(too_big) / (1024.0 * 1024.0));
    EXPECT_NE(message.find("out of device memory: test buffer needs " + std::string(size)), std::string::npos)
        << message;
  }
}

// Dynamic range: the splat sums in 64-bit fixed point. The same box lit 1e-4 and 1e6 times as brightly must give the
// same image scaled by the same factor (no overflow at the top, no lost bits at the bottom), every pixel finite and
// non-negative.
TEST(HardCases, LightOverTenDecadesScalesTheImageExactly) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 48;
  settings.light_samples = 4;
  // Without the light guide: its choices (which clusters a record aims at, in which order) compare fluxes, and
  // emission times 1e6 rounds them differently, which may move a guided ray (noise-level changes, not scaling ones).
  settings.cache.guide_rays = 0;
  const Scene original = make_cornell_box();
  const RenderedImage base = render(test::gpu(), original, settings);
  for (float factor : {1e-4f, 1e6f}) {
    Scene scaled = original;
    for (SceneMaterial& m : scaled.materials) m.emission *= factor;
    RenderedImage img = render(test::gpu(), scaled, settings);
    ASSERT_EQ(img.stats.irradiance.records, base.stats.irradiance.records) << "placement does not depend on brightness";
    double worst = 0.0;
    for (size_t i = 0; i < img.indirect.size(); ++i) {
      ASSERT_TRUE(std::isfinite(img.indirect[i]) && img.indirect[i] >= 0.0f) << "pixel value " << i;
      double expected = double(base.indirect[i]) * factor;
      if (base.indirect[i] > 0.0f) worst = std::max(worst, std::fabs(img.indirect[i] - expected) / expected);
    }
    std::printf("emission x %g: largest relative difference %.2e\n", factor, worst);
    EXPECT_LT(worst, 1e-4) << "emission x " << factor;
  }
}

// Degenerate input geometry: zero-area and duplicated triangles, a camera grazing the floor from inside the box (so
// records sit next to the eye and most of the view is one plane seen edge-on) and pixels that see nothing. Every
// pixel stays finite and non-negative, nothing is left uncovered and the duplicates change no pixel.
TEST(HardCases, DegenerateTrianglesAndAGrazingCameraStayFinite) {
  Scene scene = make_cornell_box();
  const size_t original_triangles = scene.triangle_count();
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 48;
  settings.light_samples = 4;
  scene.cameras[0].eye = glm::vec3(278.0f, 0.05f, 100.0f);   // a twentieth of a unit above the floor
  scene.cameras[0].target = glm::vec3(278.0f, 0.0f, -500.0f);  // along it, out of the open front
  scene.cameras[0].yfov = 2.0f;                                // wide: the open front lets pixels see nothing
  const RenderedImage clean = render(test::gpu(), scene, settings);
  for (size_t t = 0; t < original_triangles; ++t) {
    glm::vec3 a = scene.positions[3 * t], b = scene.positions[3 * t + 1];
    scene.add_triangle(a, b, b, scene.triangle_material[t]);                       // zero area: two corners equal
    scene.add_triangle(a, b, a + 2.0f * (b - a), scene.triangle_material[t]);      // zero area: collinear
    // A duplicate, unless it emits: two coincident emitters are two lights (as authored), one surface to a ray.
    if (scene.materials[scene.triangle_material[t]].emission == glm::vec3(0.0f))
      scene.add_triangle(a, b, scene.positions[3 * t + 2], scene.triangle_material[t]);
  }
  const RenderedImage degenerate = render(test::gpu(), scene, settings);
  size_t empty = 0;
  for (const RenderedImage* img : {&clean, &degenerate}) {
    EXPECT_EQ(img->stats.irradiance.uncovered_pixels, 0u);
    for (size_t i = 0; i < img->color.size(); ++i)
      ASSERT_TRUE(std::isfinite(img->color[i]) && img->color[i] >= 0.0f) << "pixel value " << i;
  }
  for (int t : clean.triangle) empty += t < 0;
  EXPECT_GT(empty, 0u) << "the view should include pixels that see no geometry";
  EXPECT_LT(image_error(degenerate.indirect, clean.indirect).rel_mse, 1e-6) << "degenerate triangles changed the image";
  EXPECT_LT(image_error(degenerate.direct, clean.direct).rel_mse, 1e-6) << "degenerate triangles changed the image";
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// The Cornell box with a metal floor (base 0.9) of the given roughness.
Scene cornell_with_metal_floor(float roughness) {
  Scene s = make_cornell_box();
  s.materials.push_back({"metal floor", glm::vec4(0.9f, 0.9f, 0.9f, 1.0f), -1, glm::vec3(0.0f), false});
  SceneMaterial& metal = s.materials.back();
  metal.metallic = 1.0f;
  metal.roughness = roughness;
  metal.specular = 1.0f;
  const float floor_y = s.bounds_min().y;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::vec3 *v = &s.positions[3 * t];
    if (std::max({v[0].y, v[1].y, v[2].y}) < floor_y + 1e-3f) s.triangle_material[t] = uint32_t(s.materials.size() - 1);
  }
  return s;
}

double floor_indirect_mean(const Scene& s, const RenderedImage& img) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < img.triangle.size(); ++p) {
    if (img.triangle[p] < 0 || s.triangle_material[size_t(img.triangle[p])] != s.materials.size() - 1) continue;
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(img.indirect[3 * p + c]) && img.indirect[3 * p + c] >= 0.0f);
      sum += img.indirect[3 * p + c];
    }
    ++n;
  }
  EXPECT_GT(n, 100u);
  return sum / double(3 * n);
}

// Issue 10 part 5 with radiance caching: the boundary between cached (roughness >= HSH_MIN_ROUGHNESS) and per-pixel
// sampled glossy light must not show, and the highest HSH order offered must stay finite and agree too. The floor's
// mean indirect light at roughness just below the boundary (sampled), at it (cached, order chosen from the roughness)
// and at it with --hsh-order HSH_MAX_ORDER, against path tracing at the boundary.
TEST(HardCases, RadianceCacheBoundaryAndHighestOrderAgreeWithPathTracing) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 48;
  settings.light_samples = 4;
  const Scene at = cornell_with_metal_floor(HSH_MIN_ROUGHNESS), below = cornell_with_metal_floor(0.4499f);
  const double cached = floor_indirect_mean(at, render(test::gpu(), at, settings));
  const double sampled = floor_indirect_mean(below, render(test::gpu(), below, settings));
  settings.hsh_order = HSH_MAX_ORDER;
  const RenderedImage highest_image = render(test::gpu(), at, settings);
  const double highest = floor_indirect_mean(at, highest_image);
  RenderSettings path = settings;
  path.gi = GiMethod::path;
  path.path.samples = 1024;
  path.path.pixel_area = false;  // the points the cache shades: the floor's pixels are the same ones
  const double reference = floor_indirect_mean(at, render(test::gpu(), at, path));
  std::printf("metal floor's mean indirect: sampled at 0.4499 %.4f, cached at 0.45 %.4f, order %d %.4f (order used "
              "%u), path-traced %.4f\n",
              sampled, cached, HSH_MAX_ORDER, highest, highest_image.stats.radiance.order, reference);
  EXPECT_NEAR(sampled, reference, 0.05 * reference);
  EXPECT_NEAR(cached, reference, 0.1 * reference);
  EXPECT_NEAR(highest, reference, 0.1 * reference);
  EXPECT_EQ(highest_image.stats.radiance.order, unsigned(HSH_MAX_ORDER));
}

}  // namespace
}  // namespace rcsplat

namespace rcsplat {
namespace {

// Two Cornell boxes side by side, the right one's ceiling light `dim` times the left one's. Both open toward the
// camera (-z), so no light of one reaches the inside of the other in one bounce. The camera sees into both.
Scene two_boxes(float dim) {
  Scene left = make_cornell_box(), s = left;
  const float shift = 1.2f * (left.bounds_max().x - left.bounds_min().x);
  const uint32_t materials = uint32_t(s.materials.size());
  for (SceneMaterial m : left.materials) {
    m.emission *= dim;
    s.materials.push_back(m);
  }
  for (size_t t = 0; t < left.triangle_count(); ++t) {
    const glm::vec3* v = &left.positions[3 * t];
    glm::vec3 d(shift, 0.0f, 0.0f);
    s.add_triangle(v[0] + d, v[1] + d, v[2] + d, materials + left.triangle_material[t]);
  }
  SceneCamera camera = s.cameras.empty() ? s.default_camera() : s.cameras[0];
  const glm::vec3 centre = 0.5f * (s.bounds_min() + s.bounds_max());
  camera.target = glm::vec3(centre.x, centre.y, 0.0f);  // the boxes open toward -z, as the built-in one does
  camera.eye = glm::vec3(centre.x, centre.y, -1.4f * shift);
  camera.yfov = 0.8f;
  s.cameras = {camera};
  return s;
}

// Dynamic range in one frame: one room lit a million times more brightly than the other. The dim room's indirect light
// must be what it is with the bright room's light off, to within the noise (light samples now also go to the bright
// room's emitter, which the dim room cannot see), and every pixel finite and non-negative: nothing lost to the
// fixed-point sums, and no room starved of light samples (with emitters chosen by power alone its light vanished).
TEST(HardCases, RoomsAMillionTimesApartInOneFrame) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = 96;
  settings.height = 48;
  settings.light_samples = 4;
  const Scene both = two_boxes(1e-6f);
  Scene dim_only = both;
  for (size_t m = 0; m < dim_only.materials.size() / 2; ++m) dim_only.materials[m].emission = glm::vec3(0.0f);
  const RenderedImage together = render(test::gpu(), both, settings), alone = render(test::gpu(), dim_only, settings);
  double dim_together = 0.0, dim_alone = 0.0, bright = 0.0;
  size_t dim_pixels = 0, bright_pixels = 0;
  for (size_t p = 0; p < together.triangle.size(); ++p) {
    for (int c = 0; c < 3; ++c)
      ASSERT_TRUE(std::isfinite(together.indirect[3 * p + c]) && together.indirect[3 * p + c] >= 0.0f);
    if (together.triangle[p] < 0) continue;
    if (both.triangle_material[size_t(together.triangle[p])] < both.materials.size() / 2) {
      bright += together.indirect[3 * p + 1];
      ++bright_pixels;
    } else {
      dim_together += together.indirect[3 * p + 1];
      dim_alone += alone.indirect[3 * p + 1];
      ++dim_pixels;
    }
  }
  ASSERT_GT(dim_pixels, 500u);
  ASSERT_GT(bright_pixels, 500u);
  bright /= double(bright_pixels);
  dim_together /= double(dim_pixels);
  dim_alone /= double(dim_pixels);
  std::printf("mean indirect (green): bright room %.4g; dim room %.4g, with its light alone %.4g\n", bright,
              dim_together, dim_alone);
  EXPECT_NEAR(dim_together, dim_alone, 0.05 * dim_alone);
  // The rooms differ only in their lights (and in the angle the camera sees them at): not starved.
  EXPECT_GT(dim_together / bright, 0.5e-6);
}

}  // namespace
}  // namespace rcsplat
