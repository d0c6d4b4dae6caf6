// The white furnace for the BRDF in the renderer (issue 9, item 1). Inside a closed sphere whose every triangle emits
// radiance Le, a surface sees Le from every direction, so its reflected direct light is its directional albedo times
// Le, whatever the lobe: this checks the direct pass's light sampling and, for glossy lobes, its multiple importance
// sampling against BRDF samples (a wrong weight counts the emitters twice or not at all). One bounce later, a
// direction at theta_i from the normal meets the sphere at the same angle (the chord's two ends are alike), where the
// light reflected back is Le times the albedo at theta_i: the path tracer's indirect light must be
// Le * integral of f cos(theta_i) albedo(theta_i), which the host computes in double (tests/brdf_reference.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "brdf_reference.h"
#include "render/renderer.h"
#include "scene/procedural.h"
#include "test_support.h"

namespace rcsplat {
namespace {

using brdf_reference::Material;
using brdf_reference::Vec;

// A function of cos(theta_o) on [0, 1], tabulated at nodes (i + 0.5) / n and read linearly (clamped at the ends).
struct AngleTable {
  std::vector<double> values;
  double operator()(double cos_o) const {
    double x = std::clamp(cos_o * double(values.size()) - 0.5, 0.0, double(values.size() - 1));
    size_t i = std::min(size_t(x), values.size() - 2);
    double f = x - double(i);
    return values[i] * (1.0 - f) + values[i + 1] * f;
  }
};

Vec view_at(double cos_o) { return Vec{std::sqrt(std::max(1.0 - cos_o * cos_o, 0.0)), 0.0, cos_o}; }

TEST(Furnace, ClosedEmittingSphereReflectsTheAlbedoThenTheAlbedoOfTheAlbedo) {
  const float emitted = 1.0f;
  const int nodes = 48, quadrature = 160;
  for (float metallic : {0.0f, 1.0f}) {
    for (float roughness : {0.05f, 0.3f, 0.6f, 1.0f}) {
      Material m{{1.0, 1.0, 1.0}, metallic, roughness, 1.0};
      AngleTable albedo, bounced;
      for (int i = 0; i < nodes; ++i)
        albedo.values.push_back(brdf_reference::reference_albedo(m, view_at((i + 0.5) / nodes), brdf_reference::DiffuseWeight::view_albedo, quadrature)[0]);
      for (int i = 0; i < nodes; ++i)
        bounced.values.push_back(
            brdf_reference::reference_reflected(m, view_at((i + 0.5) / nodes), albedo, brdf_reference::DiffuseWeight::view_albedo, quadrature)[0]);

      Scene scene = make_icosphere(4, 1.0f, 0.0f);
      for (SceneMaterial& sm : scene.materials) {
        sm.base_color = glm::vec4(1.0f);
        sm.emission = glm::vec3(emitted);
        sm.double_sided = true;
        sm.metallic = metallic;
        sm.roughness = roughness;
        sm.specular = 1.0f;
      }
      scene.lights.clear();
      scene.cameras[0].eye = glm::vec3(0.2f, 0.1f, 0.5f);
      scene.cameras[0].target = glm::vec3(-0.6f, 0.0f, -1.0f);
      scene.cameras[0].yfov = 1.4f;
      RenderSettings settings = test::one_bounce_one_sample();
      settings.width = settings.height = 32;
      settings.light_samples = 64;
      settings.gi = GiMethod::path;
      settings.path.samples = 64;
      settings.path.stratified = true;
      RenderedImage img = render(test::gpu(), scene, settings);
      ASSERT_TRUE(img.stats.scene.specular_brdf);

      // Pixels whose view is not near grazing: there a facet (the shading normal is radial, the facet flat) hides
      // part of the lobe.
      double direct_sum = 0.0, direct_sq = 0.0, expected_direct = 0.0;
      double indirect_diff = 0.0, indirect_var = 0.0, expected_indirect = 0.0;
      size_t count = 0;
      for (size_t i = 0; i < img.triangle.size(); ++i) {
        ASSERT_GE(img.triangle[i], 0);
        glm::vec3 p(img.position[3 * i], img.position[3 * i + 1], img.position[3 * i + 2]);
        glm::vec3 n(img.normal[3 * i], img.normal[3 * i + 1], img.normal[3 * i + 2]);
        double cos_o = glm::dot(n, glm::normalize(scene.cameras[0].eye - p));
        if (cos_o < 0.3) continue;
        for (int c = 0; c < 3; ++c) {
          double d = img.direct[3 * i + size_t(c)], v = img.indirect[3 * i + size_t(c)];
          ASSERT_TRUE(std::isfinite(d) && d >= 0.0 && std::isfinite(v) && v >= 0.0);
        }
        double ratio = img.direct[3 * i] / (emitted * albedo(cos_o));
        direct_sum += ratio;
        direct_sq += ratio * ratio;
        expected_direct += emitted * albedo(cos_o);
        indirect_diff += img.indirect[3 * i] - emitted * bounced(cos_o);
        indirect_var += img.indirect_variance[3 * i];
        expected_indirect += emitted * bounced(cos_o);
        ++count;
      }
      ASSERT_GT(count, 300u);
      double mean_ratio = direct_sum / double(count);
      double ratio_se = std::sqrt(std::max(direct_sq / double(count) - mean_ratio * mean_ratio, 0.0) / double(count));
      std::printf("metallic %.0f roughness %.2f: direct / (albedo Le) = %.4f (standard error %.4f); indirect / "
                  "expected = %.4f (standard error %.4f)\n",
                  metallic, roughness, mean_ratio, ratio_se, 1.0 + indirect_diff / expected_indirect,
                  std::sqrt(indirect_var) / expected_indirect);
      // Bounds: five standard errors of the image's mean, plus 0.5% for the tessellation (facets sit up to 0.07% of
      // the radius inside the sphere and tilt up to 2 degrees from the radial normal) and the tables' interpolation.
      EXPECT_NEAR(mean_ratio, 1.0, 5.0 * ratio_se + 0.005) << "metallic " << metallic << " roughness " << roughness;
      EXPECT_NEAR(indirect_diff / expected_indirect, 0.0, 5.0 * std::sqrt(indirect_var) / expected_indirect + 0.005)
          << "metallic " << metallic << " roughness " << roughness;
    }
  }
}

}  // namespace
}  // namespace rcsplat
