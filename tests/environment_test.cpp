// Light from outside the scene (--sky, --environment; kernels/environment.h, scene/environment.h): the furnace case,
// the map's orientation against an independent double-precision lookup, importance sampling against uniform
// sampling, and the loader's errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/environment.h"
#include "scene/procedural.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

constexpr double kPi = 3.14159265358979323846;

SceneCamera looking_at(const glm::vec3& eye, const glm::vec3& target, float yfov) {
  SceneCamera c;
  c.eye = eye;
  c.target = target;
  c.yfov = yfov;
  c.aspect = 1.0f;
  return c;
}

// A square of side 2 in the plane y = 0, facing +Y.
Scene white_plane(float albedo) {
  Scene s;
  s.source = "white plane";
  s.materials.push_back({"white", {albedo, albedo, albedo, 1.0f}, -1, {0, 0, 0}, false});
  s.add_quad({-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, 0);
  s.cameras.push_back(looking_at({0.0f, 3.0f, 0.5f}, {0.0f, 0.0f, 0.0f}, 0.9f));
  return s;
}

Scene white_sphere(float albedo) {
  Scene s = make_icosphere(3, 1.0f, 0.0f);
  s.source = "white sphere";
  s.materials[0].base_color = {albedo, albedo, albedo, 1.0f};
  // Flat facets: with radial normals, a facet's shading hemisphere dips below its plane and loses up to 0.3% of the
  // sky there, a property of the mesh, not of the light.
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::vec3 n = glm::normalize(
        glm::cross(s.positions[3 * t + 1] - s.positions[3 * t], s.positions[3 * t + 2] - s.positions[3 * t]));
    for (int k = 0; k < 3; ++k) s.normals[3 * t + k] = n;
  }
  s.lights.clear();
  s.cameras.assign(1, looking_at({0.0f, 0.5f, 3.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
  return s;
}

// The furnace: a white Lambertian surface under a uniform sky of radiance L that it sees all of reflects rho L, and the
// sky seen directly is L. The plane sees only sky; so does every point of a convex sphere. The path tracer's cosine
// samples all escape, so its estimate is exact; the cache's records are exact too (uniform radiance over each
// stratum) and its rotation gradient sums to zero over the strata, so interpolation between the sphere's normals adds
// only rounding. Tolerance: 1e-4 relative, float rounding of sums over hundreds of strata and records.
TEST(Environment, FurnaceWhitePlaneAndSphereUnderUniformSkyReflectAlbedoTimesSky) {
  const float albedo = 0.8f;
  const glm::vec3 sky(0.5f, 1.0f, 2.0f);
  for (Scene scene : {white_plane(albedo), white_sphere(albedo)}) {
    EnvironmentSettings e;
    e.sky = sky;
    scene.environment = make_environment(e);
    for (GiMethod gi : {GiMethod::splat, GiMethod::path}) {
      RenderSettings settings = test::one_bounce_one_sample();
      settings.width = settings.height = 48;
      settings.gi = gi;
      settings.path.samples = 8;
      const RenderedImage image = render(test::gpu(), scene, settings);
      size_t surface = 0, background = 0;
      for (size_t i = 0; i < image.triangle.size(); ++i) {
        const bool hit = image.triangle[i] >= 0;
        surface += hit;
        background += !hit;
        for (int c = 0; c < 3; ++c) {
          const float expected = hit ? albedo * sky[c] : sky[c];
          ASSERT_NEAR(image.color[3 * i + c], expected, 1e-4f * expected)
              << scene.source << ", " << gi_method_name(gi) << ", pixel " << i << " channel " << c;
          ASSERT_EQ(image.direct[3 * i + c], 0.0f) << "a uniform sky has no peak for shadow rays";
        }
      }
      EXPECT_GT(surface, 300u) << scene.source;
      EXPECT_GT(background, 100u) << scene.source;
    }
  }
}

// The background the camera sees, against a lookup written here in double precision: direction -> map direction
// (rotated about +Y) -> u = (1 + atan2(x, -z) / pi) / 2, v = acos(y) / pi -> texel. A map of distinct texels and a
// random rotation; camera rays away from texel borders (a float ray may round across one) must match exactly.
TEST(Environment, BackgroundLooksUpTheRotatedMapAsAHostDoublePrecisionLookup) {
  const int w = 16, h = 8;
  std::vector<float> rgb(size_t(w) * h * 3);
  for (int t = 0; t < w * h; ++t) {
    rgb[3 * t + 0] = float(t % w) + 1.0f;
    rgb[3 * t + 1] = float(t / w) + 1.0f;
    rgb[3 * t + 2] = 0.5f;
  }
  const std::string path = test::scratch_dir() + "/map.exr";
  write_exr(path, w, h, {{"", {"R", "G", "B"}, &rgb}});
  std::mt19937 rng(7);
  for (float rotation : {0.0f, 90.0f, std::uniform_real_distribution<float>(-180.0f, 180.0f)(rng)}) {
    Scene scene = white_plane(0.5f);
    scene.cameras.assign(1, looking_at({0.0f, 0.5f, 0.0f}, {0.3f, 0.9f, -1.0f}, 2.6f));
    EnvironmentSettings e;
    e.file = path;
    e.rotation_degrees = rotation;
    scene.environment = make_environment(e);
    RenderSettings settings = test::one_bounce_one_sample();
    settings.width = settings.height = 40;
    settings.gi = GiMethod::none;
    const RenderedImage image = render(test::gpu(), scene, settings);
    const SceneCamera cam = scene.cameras[0];
    const glm::dvec3 forward = glm::normalize(glm::dvec3(cam.target - cam.eye));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(cam.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tan_half = std::tan(0.5 * double(cam.yfov));
    const double angle = double(rotation) * kPi / 180.0;
    size_t checked = 0;
    for (int y = 0; y < settings.height; ++y) {
      for (int x = 0; x < settings.width; ++x) {
        const size_t i = size_t(y) * settings.width + x;
        if (image.triangle[i] >= 0) continue;
        const double sx = (2.0 * (x + 0.5) / settings.width - 1.0) * tan_half;
        const double sy = (1.0 - 2.0 * (y + 0.5) / settings.height) * tan_half;
        const glm::dvec3 d = glm::normalize(forward + sx * right + sy * up);
        // World to map: rotate by -angle about +Y.
        const glm::dvec3 m(std::cos(angle) * d.x - std::sin(angle) * d.z, d.y,
                           std::sin(angle) * d.x + std::cos(angle) * d.z);
        const double u = 0.5 * (1.0 + std::atan2(m.x, -m.z) / kPi), v = std::acos(m.y) / kPi;
        const double fu = u * w, fv = v * h;
        if (std::abs(fu - std::round(fu)) < 1e-3 || std::abs(fv - std::round(fv)) < 1e-3) continue;
        const int i_tex = std::min(int(fu), w - 1), j_tex = std::min(int(fv), h - 1);
        ASSERT_EQ(image.emission[3 * i + 0], float(i_tex) + 1.0f) << "rotation " << rotation << ", pixel " << i;
        ASSERT_EQ(image.emission[3 * i + 1], float(j_tex) + 1.0f) << "rotation " << rotation << ", pixel " << i;
        ++checked;
      }
    }
    EXPECT_GT(checked, 800u) << "rotation " << rotation;
  }
}

// The peak's tables on the host: the peak and the smooth part add up to the map, no smooth texel exceeds the
// threshold, and the density the kernels use (peak luminance / peak_power per solid angle) integrates to one.
TEST(Environment, PeakAndSmoothPartsSplitTheMapAndThePeakDensityIntegratesToOne) {
  Environment e;
  e.width = 32;
  e.height = 16;
  e.source = "test";
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int t = 0; t < e.width * e.height; ++t)
    e.radiance.push_back(glm::vec3(uniform(rng), uniform(rng), uniform(rng)) * (t % 37 == 0 ? 500.0f : 1.0f));
  const PackedEnvironment p = pack_environment(e);
  ASSERT_GT(p.peak_power, 0.0f);
  const double threshold = kEnvironmentPeakOverMean * p.mean_luminance;
  double integral = 0.0;
  for (int j = 0; j < e.height; ++j) {
    for (int i = 0; i < e.width; ++i) {
      const size_t t = size_t(j) * e.width + i;
      const glm::dvec3 c(e.radiance[t]);
      const double smooth = p.texels[4 * t + 3];
      const double lum = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
      EXPECT_LE(smooth * lum, threshold * (1.0 + 1e-6));
      EXPECT_TRUE(smooth == 1.0 || std::abs(smooth * lum - threshold) < 1e-5 * threshold);
      integral += (1.0 - smooth) * lum / double(p.peak_power) * environment_row_solid_angle(j, e.height) / e.width;
    }
  }
  EXPECT_NEAR(integral, 1.0, 1e-5);
  EXPECT_GT(p.peak_fraction, 0.5);
}

// A 32 x 16 map: a sun of six texels (radiance 60 to 70, 90% of the map's power) above the horizon, a blue-ish sky
// and dark ground. Returns its texels.
std::vector<float> write_sun_map(const std::string& path) {
  const int w = 32, h = 16;
  std::vector<float> rgb(size_t(w) * h * 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < 3; ++c) {
        const bool sun = j >= 4 && j < 6 && i >= 12 && i < 15;
        rgb[3 * (size_t(j) * w + i) + c] = sun ? 60.0f + 5.0f * c : j < h / 2 ? 0.3f + 0.1f * c : 0.05f;
      }
  write_exr(path, w, h, {{"", {"R", "G", "B"}, &rgb}});
  return rgb;
}

// The furnace with a sun: a white plane under a map reflects rho / pi times the irradiance, integrated here in double
// precision texel by texel (a row's cosine-weighted solid angle is (2 pi / w) (sin^2 theta_1 - sin^2 theta_0) / 2 above
// the horizon). The sun reaches the plane through the pixels' shadow rays (direct layer), the sky through the
// gathering rays (indirect): counting either twice or not at all, or a wrong density, misses by far more than the
// tolerance, 1% on the mean over the plane's pixels (the estimates' noise averages to well below it).
TEST(Environment, WhitePlaneUnderASunMapReflectsAlbedoTimesItsIrradiance) {
  const int w = 32, h = 16;
  const std::string path = test::scratch_dir() + "/sun.exr";
  const std::vector<float> rgb = write_sun_map(path);
  glm::dvec3 irradiance(0.0);
  for (int j = 0; j < h / 2; ++j) {
    const double s0 = std::sin(kPi * j / h), s1 = std::sin(kPi * (j + 1) / h);
    const double cosine_solid_angle = (2.0 * kPi / w) * 0.5 * (s1 * s1 - s0 * s0);
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < 3; ++c) irradiance[c] += rgb[3 * (size_t(j) * w + i) + c] * cosine_solid_angle;
  }
  const float albedo = 0.7f;
  Scene scene = white_plane(albedo);
  EnvironmentSettings e;
  e.file = path;
  e.rotation_degrees = 30.0f;
  scene.environment = make_environment(e);
  for (GiMethod gi : {GiMethod::splat, GiMethod::path}) {
    RenderSettings settings = test::one_bounce_one_sample();
    settings.width = settings.height = 32;
    settings.gi = gi;
    settings.path.samples = 16;
    const RenderedImage image = render(test::gpu(), scene, settings);
    glm::dvec3 sum(0.0);
    size_t count = 0;
    for (size_t i = 0; i < image.triangle.size(); ++i) {
      if (image.triangle[i] < 0) continue;
      ++count;
      for (int c = 0; c < 3; ++c) sum[c] += image.color[3 * i + c];
    }
    ASSERT_GT(count, 400u);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(sum[c] / count, albedo / kPi * irradiance[c], 0.01 * albedo / kPi * irradiance[c])
          << gi_method_name(gi) << ", channel " << c;
  }
}

// A map with a sun (a few bright texels) over a gradient sky lights a plane with a box on it. The peak's importance
// sampling (luminance times solid angle) and uniform sampling over the sphere estimate the same integral, in the
// direct layer (the pixels' shadow rays) and in the path tracer's indirect layer (the hits' shadow rays). Uniform
// sampling takes 16 times the samples; each is rendered with four seeds, whose spread gives each 8x8 block mean's
// standard error, and every block must agree within 5 of them (a pdf off by a solid-angle factor shifts blocks by
// tens of standard errors).
TEST(Environment, MapImportanceSamplingConvergesToTheUniformlySampledImage) {
  const std::string path = test::scratch_dir() + "/sun.exr";
  write_sun_map(path);
  Scene scene = white_plane(0.7f);
  scene.add_quad({-0.3f, 0.4f, 0.3f}, {0.3f, 0.4f, 0.3f}, {0.3f, 0.4f, -0.3f}, {-0.3f, 0.4f, -0.3f}, 0);  // a shade
  scene.cameras.assign(1, looking_at({0.0f, 2.5f, 1.5f}, {0.0f, 0.0f, 0.0f}, 0.9f));
  EnvironmentSettings e;
  e.file = path;
  e.rotation_degrees = 30.0f;
  scene.environment = make_environment(e);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 32;
  settings.gi = GiMethod::path;
  settings.path.samples = 64;
  settings.bounces = 2;
  settings.light_samples = 256;
  auto renders = [&](const RenderSettings& base) {
    std::vector<RenderedImage> images;
    for (unsigned seed = 1; seed <= 4; ++seed) {
      RenderSettings s = base;
      s.seed = seed;
      images.push_back(render(test::gpu(), scene, s));
    }
    return images;
  };
  const std::vector<RenderedImage> importance = renders(settings);
  settings.forced_switches = {"ENVIRONMENT_UNIFORM_SAMPLING"};
  settings.light_samples = 4096;
  settings.path.samples = 256;
  const std::vector<RenderedImage> uniform = renders(settings);
  const int block = 8, blocks = settings.width / block;
  for (const char* layer : {"direct", "indirect"}) {
    // Mean and standard error of one block's mean over a set of seeds.
    auto block_stats = [&](const std::vector<RenderedImage>& images, int bx, int by) {
      std::vector<double> means;
      for (const RenderedImage& image : images) {
        const std::vector<float>& v = std::string(layer) == "direct" ? image.direct : image.indirect;
        double s = 0.0;
        for (int y = by * block; y < (by + 1) * block; ++y)
          for (int x = bx * block; x < (bx + 1) * block; ++x)
            for (int c = 0; c < 3; ++c) s += v[3 * (size_t(y) * settings.width + x) + c];
        means.push_back(s / (3.0 * block * block));
      }
      double mean = 0.0, sq = 0.0;
      for (double m : means) mean += m / means.size();
      for (double m : means) sq += (m - mean) * (m - mean);
      return std::pair<double, double>(mean, std::sqrt(sq / (means.size() - 1) / means.size()));
    };
    double worst = 0.0, sum_importance = 0.0, sum_uniform = 0.0;
    for (int by = 0; by < blocks; ++by) {
      for (int bx = 0; bx < blocks; ++bx) {
        const auto [imp, imp_error] = block_stats(importance, bx, by);
        const auto [uni, uni_error] = block_stats(uniform, bx, by);
        const double error = std::hypot(imp_error, uni_error);
        const double z = imp == uni ? 0.0 : std::abs(imp - uni) / std::max(error, 1e-4 * uni);
        worst = std::max(worst, z);
        sum_importance += imp;
        sum_uniform += uni;
      }
    }
    EXPECT_LT(worst, 5.0) << layer;
    EXPECT_GT(sum_uniform, 0.0) << layer << ": the sun must light the scene";
    EXPECT_NEAR(sum_importance / sum_uniform, 1.0, 0.02) << layer;
  }
}

TEST(Environment, BadMapsAndSettingsAreRefusedNamingTheFileOrOption) {
  const std::string dir = test::scratch_dir();
  auto message = [](const EnvironmentSettings& e) {
    try {
      make_environment(e);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EnvironmentSettings missing;
  missing.file = dir + "/absent.hdr";
  EXPECT_NE(message(missing).find("absent.hdr"), std::string::npos) << message(missing);
  std::vector<float> rgb = {1.0f, 1.0f, 1.0f, -1.0f, 0.0f, 0.0f};
  write_exr(dir + "/negative.exr", 2, 1, {{"", {"R", "G", "B"}, &rgb}});
  EnvironmentSettings negative;
  negative.file = dir + "/negative.exr";
  EXPECT_NE(message(negative).find("negative.exr: texel (1, 0)"), std::string::npos) << message(negative);
  rgb[3] = 1e30f;
  write_exr(dir + "/bright.exr", 2, 1, {{"", {"R", "G", "B"}, &rgb}});
  EnvironmentSettings overflow;
  overflow.file = dir + "/bright.exr";
  overflow.intensity = 1e30f;
  EXPECT_NE(message(overflow).find("bright.exr: --environment-intensity"), std::string::npos) << message(overflow);
  test::write_file(dir + "/garbage.hdr", "#?RADIANCE\nnot a picture");
  negative.file = dir + "/garbage.hdr";
  EXPECT_NE(message(negative).find("garbage.hdr"), std::string::npos) << message(negative);
  EnvironmentSettings both;
  both.sky = glm::vec3(1.0f);
  both.file = dir + "/bright.exr";
  EXPECT_NE(message(both).find("--sky and --environment"), std::string::npos);
  EnvironmentSettings dark_sky;
  dark_sky.sky = glm::vec3(1.0f, -1.0f, 0.0f);
  EXPECT_NE(message(dark_sky).find("--sky"), std::string::npos);
  EnvironmentSettings spin;
  spin.sky = glm::vec3(1.0f);
  spin.rotation_degrees = INFINITY;
  EXPECT_NE(message(spin).find("--environment-rotation"), std::string::npos);
}

}  // namespace
}  // namespace rcsplat
