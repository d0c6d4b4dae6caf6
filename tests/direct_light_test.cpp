// Direct light against answers known in closed form: punctual lights over a Lambertian plane, an emissive quad whose
// irradiance at a point follows from Lambert's polygon formula, and a rough dielectric plane against glTF's own model.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "brdf_reference.h"
#include "layers_reference.h"
#include "render/renderer.h"
#include "scene/packed_scene.h"
#include "scene/scene_frame.h"
#include "util/colour.h"
#include "test_support.h"

namespace rcsplat {
namespace {

using dvec3 = glm::dvec3;
const double kPi = std::numbers::pi;
const glm::vec3 kAlbedo(0.5f, 0.6f, 0.7f);

// A 40 x 40 Lambertian plane at z = 0 facing +z (triangles 0 and 1), seen from above.
Scene plane_scene() {
  Scene s;
  s.source = "test plane";
  s.materials.push_back({"plane", glm::vec4(kAlbedo, 1.0f), -1, glm::vec3(0.0f), false});
  s.add_triangle({-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, 0);
  s.add_triangle({-20, -20, 0}, {20, 20, 0}, {-20, 20, 0}, 0);
  SceneCamera cam;
  cam.eye = {0, 0, 6};
  cam.target = {0, 0, 0};
  cam.up = {0, 1, 0};
  cam.yfov = 1.2f;
  s.cameras.push_back(cam);
  return s;
}

RenderedImage render(const Scene& s, int size, unsigned light_samples) {
  RenderSettings settings = test::one_bounce_one_sample();
  settings.gi = GiMethod::none;
  settings.width = settings.height = size;
  settings.light_samples = light_samples;
  return render(test::gpu(), s, settings);
}

dvec3 position_of(const RenderedImage& img, size_t i) {
  return dvec3(img.position[3 * i], img.position[3 * i + 1], img.position[3 * i + 2]);
}
dvec3 direct_of(const RenderedImage& img, size_t i) {
  return dvec3(img.direct[3 * i], img.direct[3 * i + 1], img.direct[3 * i + 2]);
}

// Compares every plane pixel's direct radiance with albedo / pi * E(x); float arithmetic in the kernel, so a relative
// 1e-4 (plus a tiny absolute floor for the dark edges) is the tolerance.
template <typename Irradiance>
void expect_matches_analytic(const RenderedImage& img, Irradiance irradiance) {
  size_t checked = 0, lit = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    dvec3 e = irradiance(position_of(img, i));
    for (int c = 0; c < 3; ++c) {
      double expected = double(kAlbedo[c]) / kPi * e[c];
      ASSERT_NEAR(direct_of(img, i)[c], expected, 1e-4 * expected + 1e-7) << "pixel " << i;
    }
    ++checked;
    lit += e.x > 0.0;
  }
  EXPECT_GT(checked, img.triangle.size() / 2);
  EXPECT_GT(lit, checked / 10);
}

TEST(DirectLight, PointLightOverLambertianPlane) {
  Scene s = plane_scene();
  SceneLight l;
  l.position = {0.7f, -0.3f, 2.0f};
  l.intensity = {10.0f, 20.0f, 30.0f};
  s.lights.push_back(l);
  expect_matches_analytic(render(s, 64, 0), [&](dvec3 x) {
    dvec3 to = dvec3(l.position) - x;
    double d2 = glm::dot(to, to);
    double cos_theta = to.z / std::sqrt(d2);  // E = I cos(theta) / d^2
    return dvec3(l.intensity) * cos_theta / d2;
  });
}

TEST(DirectLight, SpotLightConeFollowsGltfFalloff) {
  Scene s = plane_scene();
  SceneLight l;
  l.type = LightType::spot;
  l.position = {0.0f, 0.0f, 3.0f};
  l.direction = glm::normalize(glm::vec3(0.2f, 0.1f, -1.0f));
  l.intensity = glm::vec3(50.0f);
  l.inner_cone = 0.3f;
  l.outer_cone = 0.6f;
  s.lights.push_back(l);
  double cos_outer = std::cos(double(l.outer_cone)), cos_inner = std::cos(double(l.inner_cone));
  expect_matches_analytic(render(s, 64, 0), [&](dvec3 x) {
    dvec3 to = dvec3(l.position) - x;
    double d2 = glm::dot(to, to);
    double cd = glm::dot(dvec3(l.direction), -to / std::sqrt(d2));
    double a = std::clamp((cd - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
    return dvec3(l.intensity) * (a * a) * (to.z / std::sqrt(d2)) / d2;
  });
}

// The plane with a square of `material` (half side `half`) at z = 1 above it, and a directional light of intensity 3
// travelling along `direction`.
Scene plane_under_square(const SceneMaterial& material, float half, const glm::vec3& direction) {
  Scene s = plane_scene();
  s.materials.push_back(material);
  s.add_triangle({-half, -half, 1}, {half, -half, 1}, {half, half, 1}, 1);
  s.add_triangle({-half, -half, 1}, {half, half, 1}, {-half, half, 1}, 1);
  SceneLight l;
  l.type = LightType::directional;
  l.direction = glm::normalize(direction);
  l.intensity = glm::vec3(3.0f);
  s.lights.push_back(l);
  return s;
}

TEST(DirectLight, DirectionalLightAndShadow) {
  // A small occluding square at z = 1 casts a shadow that the analytic answer includes as a projection test.
  const Scene s = plane_under_square({"blocker", glm::vec4(kAlbedo, 1.0f), -1, glm::vec3(0.0f), false}, 0.5f,
                                     glm::vec3(0.6f, 0.0f, -0.8f));
  const SceneLight& l = s.lights[0];
  RenderedImage img = render(s, 64, 0);
  size_t shadowed = 0, checked = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] > 1 || img.triangle[i] < 0) continue;  // plane pixels only
    dvec3 x = position_of(img, i);
    // Walk back toward the light to z = 1 and test the blocker's square; skip pixels at the shadow's edge.
    dvec3 at_blocker = x - dvec3(l.direction) * (1.0 / -double(l.direction.z));
    double edge = std::max(std::fabs(at_blocker.x), std::fabs(at_blocker.y));
    if (std::fabs(edge - 0.5) < 0.05) continue;
    bool in_shadow = edge < 0.5;
    double e = in_shadow ? 0.0 : 3.0 * 0.8;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(direct_of(img, i)[c], kAlbedo[c] / kPi * e, 1e-4 * e + 1e-7);
    shadowed += in_shadow;
    ++checked;
  }
  EXPECT_GT(shadowed, 20u);
  EXPECT_GT(checked, 1000u);
}

// Lambert's formula: irradiance at x (normal +z) from a uniform, one-sided polygon of radiance 1.
double polygon_irradiance(dvec3 x, const std::vector<dvec3>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    dvec3 a = glm::normalize(polygon[i] - x), b = glm::normalize(polygon[(i + 1) % polygon.size()] - x);
    dvec3 c = glm::cross(a, b);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * c.z / glm::length(c);
  }
  return 0.5 * std::fabs(sum);
}

// Pixels whose direct light is a sampled estimate: each within 5.5 standard errors of scale[c] * irradiance (the
// estimator's standard error scale[c] * sqrt(variance), z = 5.5 keeping the family-wise false-failure rate below 1e-4
// over all pixels), and the green channel's errors summed over the image within 4 of their standard errors: a bias of
// a fraction of a percent shows there.
struct SampledPixels {
  double sum_error = 0.0, sum_variance = 0.0;
  size_t checked = 0;
  void check(const RenderedImage& img, size_t i, const dvec3& scale, double irradiance, double variance) {
    for (int c = 0; c < 3; ++c) {
      const double expected = scale[c] * irradiance, sigma = scale[c] * std::sqrt(variance);
      ASSERT_NEAR(direct_of(img, i)[c], expected, 5.5 * sigma + 1e-4 * expected) << "pixel " << i;
      if (c == 1) {
        sum_error += direct_of(img, i)[c] - expected;
        sum_variance += sigma * sigma;
      }
    }
    ++checked;
  }
  void expect_unbiased() const {
    ASSERT_GT(checked, 1000u);
    EXPECT_LT(std::fabs(sum_error), 4.0 * std::sqrt(sum_variance)) << "summed error " << sum_error;
  }
};

TEST(DirectLight, EmissiveQuadMatchesPolygonFormula) {
  Scene s = plane_scene();
  const glm::vec3 radiance(2.0f, 4.0f, 8.0f);
  const float h = 1.5f, half = 0.75f;
  s.materials.push_back({"emitter", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), -1, radiance, false});
  // Facing down (-z): counter-clockwise seen from below.
  s.add_triangle({-half, -half, h}, {-half, half, h}, {half, half, h}, 1);
  s.add_triangle({-half, -half, h}, {half, half, h}, {half, -half, h}, 1);
  const unsigned samples = 64;
  RenderedImage img = render(s, 64, samples);
  std::vector<dvec3> quad = {{-half, -half, h}, {-half, half, h}, {half, half, h}, {half, -half, h}};
  // The estimator's per-sample variance, by Monte Carlo in double: stratified sampling can only lower it, so
  // sigma / sqrt(samples) bounds the render's standard error.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  double area = 4.0 * half * half;
  SampledPixels pixels;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0 || img.triangle[i] > 1) continue;
    dvec3 x = position_of(img, i);
    double e = polygon_irradiance(x, quad);
    double m1 = 0.0, m2 = 0.0;
    const int probes = 4000;
    for (int k = 0; k < probes; ++k) {
      dvec3 y(-half + 2.0 * half * uni(rng), -half + 2.0 * half * uni(rng), h);
      dvec3 to = y - x;
      double d2 = glm::dot(to, to), d = std::sqrt(d2);
      double f = (to.z / d) * (to.z / d) / d2 * area;  // cos_x cos_y / d^2 / pdf
      m1 += f;
      m2 += f * f;
    }
    m1 /= probes;
    pixels.check(img, i, dvec3(kAlbedo) / kPi * dvec3(radiance), e, std::max(0.0, m2 / probes - m1 * m1) / samples);
  }
  pixels.expect_unbiased();
}

// A grey (0.8) rough dielectric floor of this roughness, seen from near its plane as floors are, under a point light
// of intensity 10 at (0, 3, 1.5).
Scene rough_floor(float roughness) {
  Scene s = plane_scene();
  s.materials[0].base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  s.materials[0].roughness = roughness;
  s.materials[0].specular = 1.0f;
  s.cameras[0].eye = {0.0f, -6.0f, 1.0f};
  s.cameras[0].target = {0.0f, 6.0f, 0.0f};
  SceneLight l;
  l.position = {0.0f, 3.0f, 1.5f};
  l.intensity = glm::vec3(10.0f);
  s.lights.push_back(l);
  return s;
}

// What the BRDF reference needs at pixel i of a rough_floor render: the local view and light directions (the plane's
// normal is +z) and the irradiance from the scene's one light.
struct FloorPixel {
  brdf_reference::Vec wo, wi;
  double irradiance;
};
FloorPixel floor_pixel(const Scene& s, const RenderedImage& img, size_t i) {
  const dvec3 x = position_of(img, i), to_light = dvec3(s.lights[0].position) - x;
  const dvec3 to_eye = glm::normalize(dvec3(s.cameras[0].eye) - x);
  const double d2 = glm::dot(to_light, to_light);
  const dvec3 wl = to_light / std::sqrt(d2);
  return {{to_eye.x, to_eye.y, to_eye.z}, {wl.x, wl.y, wl.z}, double(s.lights[0].intensity.x) * wl.z / d2};
}

// The tolerance of a rough_floor pixel against rcsplat's model in double: the float BRDF's 1e-4, and the tabulated
// weight's bilinear error (at most 2e-3 where cos > 0.1, 0.04 below) on the floor's 0.8 / pi.
double floor_tolerance(const FloorPixel& p, double expected) {
  return 1e-4 * expected + (p.wo.z < 0.1 ? 0.04 : 2e-3) * 0.8 / kPi * p.irradiance + 1e-7;
}

// A rough dielectric (glTF's defaults with metallic 0: roughness 0.5 to 1, specular 1) seen from near its plane, as
// floors are, under a point light. glTF's appendix B weights the diffuse base by 1 - F(v.h) per light direction;
// rcsplat by one less the lobe's albedo toward the view (kernels/brdf.h says why). Each pixel must match rcsplat's
// model in double (tests/brdf_reference.h), and the plane's mean brightness appendix B's within 5% (issue 41). The
// weight rcsplat had before, 1 - F(n.v), was 30-40% darker here.
TEST(DirectLight, RoughDielectricIsAsBrightAsGltfAppendixB) {
  using brdf_reference::DiffuseWeight;
  for (float roughness : {0.5f, 0.75f, 1.0f}) {
    const Scene s = rough_floor(roughness);
    RenderedImage img = render(s, 64, 0);
    const brdf_reference::Material m{{0.8, 0.8, 0.8}, 0.0, double(roughness), 1.0};
    double rendered = 0.0, appendix_b = 0.0, view_fresnel = 0.0;
    size_t checked = 0;
    for (size_t i = 0; i < img.triangle.size(); ++i) {
      if (img.triangle[i] < 0) continue;
      const auto [wo, wi, irradiance] = floor_pixel(s, img, i);
      appendix_b += brdf_reference::reference_brdf(m, wo, wi, true, true, DiffuseWeight::per_microfacet)[0] * irradiance;
      view_fresnel += brdf_reference::reference_brdf(m, wo, wi, true, true, DiffuseWeight::view_fresnel)[0] * irradiance;
      rendered += direct_of(img, i).x;
      if (i % 4 == 0) {  // rcsplat's own model, whose weight costs a quadrature per view
        const double expected = brdf_reference::reference_brdf(m, wo, wi, true, true)[0] * irradiance;
        ASSERT_NEAR(direct_of(img, i).x, expected, floor_tolerance({wo, wi, irradiance}, expected))
            << "pixel " << i << " roughness " << roughness << " cos(theta_o) " << wo.z;
        ++checked;
      }
    }
    ASSERT_GT(checked, 400u);
    std::printf("roughness %.2f: rendered / appendix B %.4f; 1 - F(n.v) / appendix B %.4f\n", roughness,
                rendered / appendix_b, view_fresnel / appendix_b);
    EXPECT_NEAR(rendered / appendix_b, 1.0, 0.05) << "roughness " << roughness;
  }
}

// KHR_materials_specular's specularTexture: its alpha multiplies specularFactor. A rough dielectric plane whose one
// texel's alpha is 100 must shade as rcsplat's model in double (tests/brdf_reference.h) with specular 100 / 255, and
// differ from the factor's own (specular 1) by more than the tolerance. Planted: the texture ignored; it fails.
TEST(DirectLight, SpecularTextureScalesTheSpecularLayer) {
  Scene s = rough_floor(0.75f);
  SceneTexture t;
  t.width = t.height = 1;
  t.rgba = {255, 255, 255, 100};
  s.textures.push_back(t);
  s.materials[0].specular_texture = 0;
  const RenderedImage img = render(s, 64, 0);
  const brdf_reference::Material textured{{0.8, 0.8, 0.8}, 0.0, 0.75, 100.0 / 255.0}, factor{{0.8, 0.8, 0.8}, 0.0, 0.75, 1.0};
  size_t checked = 0, distinguished = 0;
  for (size_t i = 0; i < img.triangle.size(); i += 4) {
    if (img.triangle[i] < 0) continue;
    const FloorPixel p = floor_pixel(s, img, i);
    const double expected = brdf_reference::reference_brdf(textured, p.wo, p.wi, true, true)[0] * p.irradiance;
    const double tolerance = floor_tolerance(p, expected);
    ASSERT_NEAR(direct_of(img, i).x, expected, tolerance) << "pixel " << i << " cos(theta_o) " << p.wo.z;
    const double untextured = brdf_reference::reference_brdf(factor, p.wo, p.wi, true, true)[0] * p.irradiance;
    distinguished += std::fabs(untextured - expected) > tolerance;
    ++checked;
  }
  ASSERT_GT(checked, 400u);
  EXPECT_GT(distinguished, checked / 2) << "the texture must matter where it is tested";
}

// A normal map bends the shading normal (glTF: n = normalize(T x + B y + N z), (x, y, z) = (2 rgb - 1) * (scale,
// scale, 1), B = cross(N, T) * w): the plane's one texel tilts it toward +x and -y. Every pixel's direct light must be
// the BRDF evaluated in double about that normal, for a Lambertian and a rough dielectric plane, and its normal layer
// that normal. A kernel that shades with the interpolated normal, or swaps T and B, or ignores w or the scale, fails.
TEST(DirectLight, NormalMappedPlaneShadesWithTheMappedNormal) {
  using brdf_reference::Vec;
  const unsigned char texel[4] = {205, 96, 214, 255};
  const float scale = 0.8f;
  // Which way the bitangent points: w = -1 mirrors the map's y.
  for (float w : {1.0f, -1.0f}) {
    for (float roughness : {1.0f, 0.75f}) {
      Scene s = plane_scene();
      SceneTexture t;
      t.width = t.height = 1;
      t.rgba.assign(texel, texel + 4);
      s.textures.push_back(t);
      s.materials[0].normal_texture = 0;
      s.materials[0].normal_scale = scale;
      s.materials[0].roughness = roughness;
      s.materials[0].specular = roughness < 1.0f ? 1.0f : 0.0f;
      s.tangents.assign(s.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, w));
      s.cameras[0].eye = {0.0f, -5.0f, 3.0f};
      SceneLight l;
      l.position = {0.7f, -0.3f, 2.0f};
      l.intensity = glm::vec3(10.0f, 20.0f, 30.0f);
      s.lights.push_back(l);
      RenderedImage img = render(s, 64, 0);
      const dvec3 mapped = glm::normalize(dvec3((2.0 * texel[0] / 255.0 - 1.0) * scale,
                                                (2.0 * texel[1] / 255.0 - 1.0) * scale * w, 2.0 * texel[2] / 255.0 - 1.0));
      // Any frame about the mapped normal: the BRDF is isotropic.
      const dvec3 tangent = glm::normalize(glm::cross(dvec3(0.0, 1.0, 0.0), mapped)), bitangent = glm::cross(mapped, tangent);
      auto local = [&](dvec3 v) { return Vec{glm::dot(v, tangent), glm::dot(v, bitangent), glm::dot(v, mapped)}; };
      const brdf_reference::Material m{{kAlbedo.x, kAlbedo.y, kAlbedo.z}, 0.0, double(roughness), roughness < 1.0f ? 1.0 : 0.0};
      size_t checked = 0, lit = 0;
      for (size_t i = 0; i < img.triangle.size(); ++i) {
        if (img.triangle[i] < 0) continue;
        const dvec3 x = position_of(img, i), to_light = dvec3(l.position) - x;
        const double d2 = glm::dot(to_light, to_light);
        const dvec3 wi = to_light / std::sqrt(d2), wo = glm::normalize(dvec3(s.cameras[0].eye) - x);
        const double cos_mapped = glm::dot(mapped, wi);
        for (int k = 0; k < 3; ++k)
          ASSERT_NEAR(img.normal[3 * i + size_t(k)], mapped[k], 2e-6) << "pixel " << i << " w " << w;
        for (int c = 0; c < 3; ++c) {
          const double irradiance = double(l.intensity[c]) * std::max(cos_mapped, 0.0) / d2;
          double expected = roughness == 1.0f ? double(kAlbedo[c]) / kPi * irradiance : 0.0;
          double weight_error = 0.0;
          if (roughness < 1.0f) {
            // A view below the mapped normal is taken just above its horizon (kernels/brdf_frame.h view_local).
            Vec o = local(wo);
            if (o.z < 1e-4) {
              const double norm = std::sqrt(o.x * o.x + o.y * o.y + 1e-8);
              o = Vec{o.x / norm, o.y / norm, 1e-4 / norm};
            }
            const Vec in = local(wi);
            expected = cos_mapped > 0.0 ? brdf_reference::reference_brdf(m, o, in, true, true)[size_t(c)] * irradiance : 0.0;
            weight_error = (o.z < 0.1 ? 0.04 : 2e-3) * double(kAlbedo[c]) / kPi * irradiance;  // as the test above
          }
          ASSERT_NEAR(direct_of(img, i)[c], expected, 1e-4 * expected + weight_error + 1e-7)
              << "pixel " << i << " channel " << c << " w " << w << " roughness " << roughness;
        }
        ++checked;
        lit += cos_mapped > 0.0;
      }
      EXPECT_GT(checked, img.triangle.size() / 2);
      EXPECT_GT(lit, checked / 2);
    }
  }
}

// An emissive quad whose texture is bright on its left half and dim on its right (NEAREST, so the halves are
// crisp): the irradiance at each plane point is the polygon formula's for each half times that half's radiance, within
// the estimator's own noise (its variance computed in double from the emitters' selection probabilities). The
// triangle that holds more of the bright half must be chosen more often (emitters by textured power).
TEST(DirectLight, TexturedEmitterIsSampledAtItsTexels) {
  Scene s = plane_scene();
  const glm::vec3 factor(2.0f, 4.0f, 8.0f);
  const float h = 1.5f, half = 0.75f;
  SceneTexture t;
  t.width = 2;
  t.height = 1;
  t.nearest = true;
  t.rgba = {255, 255, 255, 255, 60, 60, 60, 255};
  s.textures.push_back(t);
  const double bright = 1.0, dim = srgb_to_linear(60.0 / 255.0);
  s.materials.push_back({"emitter", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), -1, factor, false});
  s.materials.back().emissive_texture = 0;
  // Facing down (-z), u along +x: u < 0.5 (x < 0) is the bright texel. Triangle 2 holds 3/4 of the bright half.
  s.add_triangle({-half, -half, h}, {-half, half, h}, {half, half, h}, 1);
  s.add_triangle({-half, -half, h}, {half, half, h}, {half, -half, h}, 1);
  const glm::vec2 uv[6] = {{0, 1}, {0, 0}, {1, 0}, {0, 1}, {1, 0}, {1, 1}};
  for (int k = 0; k < 6; ++k) s.uvs[6 + size_t(k)] = uv[k];
  const PackedScene packed = pack_scene(s);
  ASSERT_EQ(packed.emitters.size(), 2u);
  const double mean_first = 0.75 * bright + 0.25 * dim, mean_second = 0.25 * bright + 0.75 * dim;
  // The host's estimate of each triangle's mean reads 4 x 4 points or more: within 15% here.
  EXPECT_NEAR(packed.emitter_mean_luminance[0] / packed.emitter_mean_luminance[1], mean_first / mean_second,
              0.15 * mean_first / mean_second);
  EXPECT_GT(packed.emitters[0].pdf_select, packed.emitters[1].pdf_select);
  const unsigned samples = 64;
  RenderedImage img = render(s, 64, samples);
  const std::vector<dvec3> left = {{-half, -half, h}, {-half, half, h}, {0.0, half, h}, {0.0, -half, h}};
  const std::vector<dvec3> right = {{0.0, -half, h}, {0.0, half, h}, {half, half, h}, {half, -half, h}};
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double area = 2.0 * half * half;  // each triangle's
  SampledPixels pixels;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0 || img.triangle[i] > 1) continue;
    const dvec3 x = position_of(img, i);
    const double e_bright = polygon_irradiance(x, left), e_dim = polygon_irradiance(x, right);
    // The estimator in double: a triangle by its selection probability, a uniform point on it.
    double m1 = 0.0, m2 = 0.0;
    const int probes = 4000;
    for (int k = 0; k < probes; ++k) {
      const bool first = uni(rng) < packed.emitters[0].pdf_select;
      double a = uni(rng), b = uni(rng);
      if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
      const dvec3 v0(-half, -half, h), e1 = first ? dvec3(0.0, 2.0 * half, 0.0) : dvec3(2.0 * half, 2.0 * half, 0.0),
                                     e2 = first ? dvec3(2.0 * half, 2.0 * half, 0.0) : dvec3(2.0 * half, 0.0, 0.0);
      const dvec3 y = v0 + a * e1 + b * e2, to = y - x;
      const double d2 = glm::dot(to, to), cos = to.z / std::sqrt(d2);
      const double pdf_area = (first ? packed.emitters[0].pdf_select : packed.emitters[1].pdf_select) / area;
      const double f = (y.x < 0.0 ? bright : dim) * cos * cos / d2 / pdf_area;
      m1 += f;
      m2 += f * f;
    }
    m1 /= probes;
    pixels.check(img, i, dvec3(kAlbedo) / kPi * dvec3(factor), bright * e_bright + dim * e_dim,
                 std::max(0.0, m2 / probes - m1 * m1) / samples);
  }
  pixels.expect_unbiased();
}

// Alpha mode BLEND, by hashed transparency: a quad of alpha 0.3 over the lit plane, both under a directional light.
// A pixel sees the quad with probability alpha (then lit), else the plane, which the quad shadows with probability
// alpha. The mean direct light over the plane's pixels must be alpha L_quad + (1 - alpha)^2 L_plane within five
// standard errors of that three-valued mixture, and the share of pixels that see the quad alpha within five binomial
// standard errors. Blending ignored (opaque, or a hole everywhere) misses by hundreds of standard errors.
TEST(DirectLight, AlphaBlendIsSeenAndCastsShadowWithItsAlpha) {
  const double alpha = 0.3;
  SceneMaterial veil{"veil", glm::vec4(1.0f, 1.0f, 1.0f, float(alpha)), -1, glm::vec3(0.0f), true};
  veil.alpha_blend = true;
  const Scene s = plane_under_square(veil, 30.0f, glm::vec3(0.2f, 0.1f, -1.0f));
  const SceneLight& l = s.lights[0];
  const RenderedImage img = render(s, 96, 0);
  const double cos = -l.direction.z;
  const double plane = double(kAlbedo.y) / kPi * 3.0 * cos, quad = 1.0 / kPi * 3.0 * cos;
  const double mean = alpha * quad + (1.0 - alpha) * (1.0 - alpha) * plane;
  const double second = alpha * quad * quad + (1.0 - alpha) * (1.0 - alpha) * plane * plane;
  double sum = 0.0;
  size_t pixels = 0, on_quad = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    ++pixels;
    on_quad += img.triangle[i] >= 2;
    sum += direct_of(img, i).y;
  }
  ASSERT_GT(pixels, 5000u);
  const double n = double(pixels), measured = sum / n, sigma = std::sqrt((second - mean * mean) / n);
  std::printf("blend: %.5f against %.5f (sigma %.1e); %.4f of the pixels see the veil\n", measured, mean, sigma,
              double(on_quad) / n);
  EXPECT_NEAR(measured, mean, 5.0 * sigma);
  EXPECT_NEAR(double(on_quad) / n, alpha, 5.0 * std::sqrt(alpha * (1.0 - alpha) / n));
}

// Fresnel's unpolarised reflectance of a smooth interface from the side of index 1 into index n (n may be below 1:
// seen from inside), in the angles' form (sin and tan of their difference and sum), independent of the kernel's
// cosine form: 1 on total internal reflection.
double fresnel_by_angles(double cos_i, double n) {
  const double theta_i = std::acos(std::clamp(cos_i, -1.0, 1.0)), sin_t = std::sin(theta_i) / n;
  if (sin_t >= 1.0) return 1.0;
  if (theta_i < 1e-6) return std::pow((n - 1.0) / (n + 1.0), 2.0);  // normal incidence, where the angle form is 0 / 0
  const double theta_t = std::asin(sin_t);
  const double rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
  const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
  return 0.5 * (rs * rs + rp * rp);
}

SceneMaterial glass(const glm::vec3& tint, float ior) {
  SceneMaterial m{"glass", glm::vec4(tint, 1.0f), -1, glm::vec3(0.0f), true};
  m.transmission = 1.0f;
  m.roughness = 0.0f;
  m.metallic = 0.0f;
  m.specular = 1.0f;
  m.ior = ior;
  return m;
}

// Thin-walled glass (KHR_materials_transmission without a volume) over the lit plane, under a directional light, seen
// by the camera through it: the light reaches the plane through the pane, and the camera sees the plane through it,
// each keeping (1 - F) times the glass's colour at its own angle. Every plane pixel against albedo / pi E times both
// in double (Fresnel in its angles' form), at the float kernels' 1e-4. Glass taken as opaque (the shadow ray stops),
// or its Fresnel or colour dropped, misses by far more.
TEST(DirectLight, ThinGlassPassesLightAndSightWithItsColourAndFresnel) {
  const glm::vec3 tint(0.9f, 0.8f, 0.6f);
  const double ior = 1.5;
  Scene s = plane_under_square(glass(tint, float(ior)), 30.0f, glm::vec3(0.6f, 0.0f, -0.8f));
  const RenderedImage img = render(s, 64, 0);
  const dvec3 eye(s.cameras[0].eye);
  const double light_pass = 1.0 - fresnel_by_angles(0.8, ior);
  size_t checked = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    ASSERT_LT(img.triangle[i], 2) << "pixel " << i << " sees the glass itself";
    const dvec3 x = position_of(img, i), to = glm::normalize(x - eye);
    const double sight_pass = 1.0 - fresnel_by_angles(-to.z, ior);
    for (int c = 0; c < 3; ++c) {
      const double expected = double(kAlbedo[c]) / kPi * 3.0 * 0.8 * light_pass * sight_pass * double(tint[c]) * double(tint[c]);
      ASSERT_NEAR(direct_of(img, i)[c], expected, 1e-4 * expected + 1e-7) << "pixel " << i << " channel " << c;
    }
    ++checked;
  }
  EXPECT_GT(checked, 4000u);
}

// Glass with a volume (KHR_materials_volume): a slab 0.5 thick over an emissive plane, seen by an orthographic camera
// tilted 40 degrees from the vertical. Each ray refracts into the slab (Snell), crosses it along thickness / cos_t,
// attenuated by Beer-Lambert (attenuationColor at attenuationDistance), and refracts out; it keeps
// (1 - F(cos_i, n)) (1 - F(cos_t, 1 / n)) tint^2 exp(-sigma chord) of the plane's radiance, the same at every pixel that
// sees the plane through the slab. A ray taken straight through (thin), or without attenuation, misses by far more.
// Tolerance: the float kernels' 1e-4, and the chord that the rays' offsets off each face shorten (at most 1/65536 of a
// device unit each, host_device.h offset_ray_coordinate), which Beer-Lambert turns into sigma times that length.
TEST(DirectLight, GlassVolumeRefractsAndAttenuatesTheCamerasRays) {
  const glm::vec3 tint(0.95f, 0.9f, 0.85f), attenuation_color(0.5f, 0.7f, 0.9f);
  const double ior = 1.5, thickness = 0.5, attenuation_distance = 0.8, radiance = 2.0;
  Scene s;
  s.source = "test slab";
  s.materials.push_back({"emitter", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), -1, glm::vec3(float(radiance)), false});
  s.add_triangle({-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, 0);
  s.add_triangle({-20, -20, 0}, {20, 20, 0}, {-20, 20, 0}, 0);
  SceneMaterial slab = glass(tint, float(ior));
  slab.thickness = float(thickness);
  slab.attenuation_color = attenuation_color;
  slab.attenuation_distance = float(attenuation_distance);
  s.materials.push_back(slab);
  // A closed box from z = 1 to 1.5, its faces wound outward.
  const float a = 15.0f, z0 = 1.0f, z1 = 1.5f;
  auto quad = [&](glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
    s.add_triangle(p0, p1, p2, 1);
    s.add_triangle(p0, p2, p3, 1);
  };
  quad({-a, -a, z1}, {a, -a, z1}, {a, a, z1}, {-a, a, z1});  // top, +z
  quad({-a, -a, z0}, {-a, a, z0}, {a, a, z0}, {a, -a, z0});  // bottom, -z
  quad({-a, -a, z0}, {a, -a, z0}, {a, -a, z1}, {-a, -a, z1});  // -y
  quad({-a, a, z0}, {-a, a, z1}, {a, a, z1}, {a, a, z0});      // +y
  quad({-a, -a, z0}, {-a, -a, z1}, {-a, a, z1}, {-a, a, z0});  // -x
  quad({a, -a, z0}, {a, a, z0}, {a, a, z1}, {a, -a, z1});      // +x
  const double tilt = 40.0 * kPi / 180.0;
  SceneCamera cam;
  cam.orthographic = true;
  cam.eye = {float(-6.0 * std::sin(tilt)), 0.0f, float(1.5 + 6.0 * std::cos(tilt))};
  cam.target = {0.0f, 0.0f, 1.5f};
  cam.up = {0, 1, 0};
  cam.xmag = cam.ymag = 2.0f;
  s.cameras.push_back(cam);
  const RenderedImage img = render(s, 48, 0);
  const double cos_i = std::cos(tilt), sin_t = std::sin(tilt) / ior, cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double chord = thickness / cos_t;
  const double offsets = 2.0 * SceneFrame::fitted(s).scale / 65536.0 / cos_t;  // world units
  const double kept = (1.0 - fresnel_by_angles(cos_i, ior)) * (1.0 - fresnel_by_angles(cos_t, 1.0 / ior));
  size_t checked = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    ASSERT_EQ(img.triangle[i] >= 0 && img.triangle[i] < 2, true) << "pixel " << i << " must see the plane";
    for (int c = 0; c < 3; ++c) {
      const double sigma = -std::log(double(attenuation_color[c])) / attenuation_distance;
      const double expected = radiance * kept * double(tint[c]) * double(tint[c]) * std::exp(-sigma * chord);
      ASSERT_NEAR(img.emission[3 * i + c], expected, (1e-4 + sigma * offsets) * expected)
          << "pixel " << i << " channel " << c;
    }
    ++checked;
  }
  EXPECT_EQ(checked, img.triangle.size());
}

// What glass mirrors at the camera: the thin pane over the plane, seen from above, and a Lambertian ceiling at z = 8
// lit from below by a point light at z = 7. A plane pixel gets the plane's direct light through the pane (the light
// and the view each keep (1 - F) tint) plus R(view) times the ceiling's radiance where the mirrored ray meets it,
// albedo / pi I cos / d^2 (kernels/glass_mirror.cl: its direct light alone in a frame without indirect light). Every
// value in double against the float kernels' 1e-4; without the mirror pass the pixels miss by the ceiling's share.
TEST(DirectLight, GlassMirrorsTheLitSurfacesTheCameraSeesInIt) {
  const glm::vec3 tint(0.9f, 0.8f, 0.6f);
  const double ior = 1.5, ceiling_albedo = 0.8;
  Scene s = plane_scene();
  s.materials.push_back(glass(tint, float(ior)));
  s.add_triangle({-30, -30, 1}, {30, -30, 1}, {30, 30, 1}, 1);
  s.add_triangle({-30, -30, 1}, {30, 30, 1}, {-30, 30, 1}, 1);
  s.materials.push_back({"ceiling", glm::vec4(glm::vec3(float(ceiling_albedo)), 1.0f), -1, glm::vec3(0.0f), false});
  s.add_triangle({-30, -30, 8}, {30, 30, 8}, {30, -30, 8}, 2);  // facing down
  s.add_triangle({-30, -30, 8}, {-30, 30, 8}, {30, 30, 8}, 2);
  SceneLight l;
  l.position = {0.3f, 0.2f, 7.0f};
  l.intensity = {10.0f, 20.0f, 30.0f};
  s.lights.push_back(l);
  const RenderedImage img = render(s, 48, 0);
  const dvec3 eye(s.cameras[0].eye), light(l.position), intensity(l.intensity);
  size_t checked = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    ASSERT_LT(img.triangle[i], 2) << "pixel " << i << " sees the glass itself";
    const dvec3 x = position_of(img, i), view = glm::normalize(x - eye);
    // The plane's light: the point light through the pane at its own angle.
    const dvec3 to_light = light - x;
    const double d2 = glm::dot(to_light, to_light), cos_light = to_light.z / std::sqrt(d2);
    const double light_pass = 1.0 - fresnel_by_angles(cos_light, ior), view_pass = 1.0 - fresnel_by_angles(-view.z, ior);
    // The mirrored ray: from where the view crosses the pane, up to the ceiling.
    const dvec3 on_pane = eye + view * ((1.0 - eye.z) / view.z);
    const dvec3 mirrored(view.x, view.y, -view.z);
    const dvec3 on_ceiling = on_pane + mirrored * ((8.0 - on_pane.z) / mirrored.z);
    const dvec3 ceiling_to_light = light - on_ceiling;
    const double dc2 = glm::dot(ceiling_to_light, ceiling_to_light), cos_c = -ceiling_to_light.z / std::sqrt(dc2);
    const double r_view = fresnel_by_angles(-view.z, ior);
    for (int c = 0; c < 3; ++c) {
      const double plane = double(kAlbedo[c]) / kPi * intensity[c] * cos_light / d2 * light_pass * view_pass *
                           double(tint[c]) * double(tint[c]);
      const double ceiling = ceiling_albedo / kPi * intensity[c] * cos_c / dc2;
      const double expected = plane + r_view * ceiling;
      ASSERT_NEAR(direct_of(img, i)[c], expected, 1e-4 * expected + 1e-7) << "pixel " << i << " channel " << c;
    }
    ++checked;
  }
  EXPECT_GT(checked, 2000u);
}


// A UV sphere of `stacks` x `slices` about centre (radius r), wound outward, with the sphere's normals at its vertices
// (the shading normals a smooth glass ball refracts by).
void add_uv_sphere(Scene& s, dvec3 centre, double r, int stacks, int slices, uint32_t material) {
  auto at = [&](int i, int j) {
    const double theta = kPi * i / stacks, phi = 2.0 * kPi * j / slices;
    return dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  auto triangle = [&](dvec3 a, dvec3 b, dvec3 c) {
    s.add_triangle(glm::vec3(centre + r * a), glm::vec3(centre + r * b), glm::vec3(centre + r * c), material);
    const size_t n = s.normals.size();
    s.normals[n - 3] = glm::vec3(a);
    s.normals[n - 2] = glm::vec3(b);
    s.normals[n - 1] = glm::vec3(c);
  };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const dvec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i > 0) triangle(a, b, d);
      if (i + 1 < stacks) triangle(b, c, d);
    }
}

// The glass ball's mesh as the host light tracer below reads it: positions and vertex normals in double.
struct HostMesh {
  std::vector<dvec3> p, n;  // three per triangle
  // The closest hit of the ray o + t d (t > 1e-9) on the mesh: t, and the triangle and barycentrics (b1, b2).
  bool hit(dvec3 o, dvec3 d, double& t, size_t& tri, double& b1, double& b2) const {
    t = INFINITY;
    for (size_t k = 0; k < p.size(); k += 3) {
      const dvec3 e1 = p[k + 1] - p[k], e2 = p[k + 2] - p[k], q = glm::cross(d, e2);
      const double det = glm::dot(e1, q);
      if (std::abs(det) < 1e-14) continue;
      const dvec3 s = o - p[k];
      const double u = glm::dot(s, q) / det;
      if (u < 0.0 || u > 1.0) continue;
      const dvec3 r = glm::cross(s, e1);
      const double v = glm::dot(d, r) / det, tt = glm::dot(e2, r) / det;
      if (v < 0.0 || u + v > 1.0 || tt <= 1e-9 || tt >= t) continue;
      t = tt, tri = k, b1 = u, b2 = v;
    }
    return std::isfinite(t);
  }
};

// Where the light of a ray leaving o along unit d lands on the plane z = 0 after the glass mesh, by Snell's law and
// Fresnel (angles' form) at each crossing about the interpolated normal, both the reflected and the refracted branch
// followed with their weights (no randomness) until a branch weighs below 1e-4 or crosses 8 times; lands(x, y, w)
// for each branch that reaches the plane.
template <class Lands>
void trace_through_glass(const HostMesh& m, double ior, dvec3 o, dvec3 d, double w, int crossings, Lands&& lands) {
  double t, b1, b2;
  size_t k;
  if (!m.hit(o, d, t, k, b1, b2)) {
    if (d.z < 0.0) {
      const dvec3 x = o + d * (-o.z / d.z);
      lands(x.x, x.y, w);
    }
    return;
  }
  if (crossings == 8 || w < 1e-4) return;
  const dvec3 x = o + t * d, ng = glm::normalize(glm::cross(m.p[k + 1] - m.p[k], m.p[k + 2] - m.p[k]));
  const bool entering = glm::dot(ng, d) < 0.0;
  dvec3 n = glm::normalize((1.0 - b1 - b2) * m.n[k] + b1 * m.n[k + 1] + b2 * m.n[k + 2]);
  if (!entering) n = -n;  // toward the side the ray comes from
  if (glm::dot(n, d) >= 0.0) n = entering ? ng : -ng;
  const double cos_i = -glm::dot(n, d), eta = entering ? ior : 1.0 / ior;
  const double r = fresnel_by_angles(cos_i, eta);
  const dvec3 mirror = d + 2.0 * cos_i * n, side = entering ? ng : -ng;
  trace_through_glass(m, ior, x + 1e-7 * side, mirror, w * r, crossings + 1, lands);
  if (r < 1.0) {
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i)) / eta;
    const dvec3 tangent = d + cos_i * n;  // d's part along the surface, of length sin_i
    const dvec3 through = glm::normalize(tangent / eta - std::sqrt(1.0 - sin_t * sin_t) * n);
    trace_through_glass(m, ior, x - 1e-7 * side, through, w * (1.0 - r), crossings + 1, lands);
  }
}

// --light-through-glass caustics: a clear glass ball (radius 1, a volume, ior 1.5) between a point light and the
// Lambertian plane. The ball stops the shadow rays, and the light it focuses reaches the plane by the glass caustic map.
// Against a light tracer in double on the host (trace_through_glass over the same mesh and normals, every branch
// followed), the mean irradiance of the plane over discs about the spot below the ball (all inside the ball's
// geometric shadow, where no shadow ray reaches) must agree within four standard errors of the two estimates (the
// rendered pixels' spread in the disc, the host photons' spread) plus the map's blur at the disc's edge: the light of
// the ring one photon's spread either side of the edge, the spread taken from the host's density of photons there.
// Shadow rays passing the ball straight (the default's model) add a flat tinted light there (at the widest disc 2.7
// against 1.73), and a map without the ball's light leaves it dark.
TEST(DirectLight, GlassBallFocusesItsLightAsAHostLightTracerDoes) {
  const double ior = 1.5, ball_z = 2.5, light_z = 6.0, intensity = 40.0;
  Scene s = plane_scene();
  SceneMaterial ball = glass(glm::vec3(1.0f), float(ior));
  ball.thickness = 1.0f;
  s.materials.push_back(ball);
  const int stacks = 12, slices = 24;
  add_uv_sphere(s, dvec3(0.0, 0.0, ball_z), 1.0, stacks, slices, 1);
  SceneLight l;
  l.position = {0.0f, 0.0f, float(light_z)};
  l.intensity = glm::vec3(float(intensity));
  s.lights.push_back(l);
  s.glass_light.caustics = true;
  // Each photon's radius holding 256 neighbours, so that the pixels in a disc read each photon's light between them
  // (at the default 64 the focus's photons spread over less than a pixel, and the pixels sample them hit or miss).
  s.glass_light.neighbours = 256;
  s.glass_light.photons = 1u << 16;  // aimed at the ball, most land past it: enough, and the map's setup stays short
  // Tilted 60 degrees about y, so that the plane under the ball is seen beside it, not through it.
  const double tilt = 60.0 * kPi / 180.0;
  s.cameras[0].orthographic = true;
  s.cameras[0].eye = {float(-10.0 * std::sin(tilt)), 0.0f, float(10.0 * std::cos(tilt))};
  s.cameras[0].target = {0.0f, 0.0f, 0.0f};
  s.cameras[0].xmag = s.cameras[0].ymag = 1.3f;  // every disc below in view
  const RenderedImage img = render(s, 256, 0);
  ASSERT_TRUE(img.stats.scene.glass_caustics);
  const double photon_flux = intensity * 4.0 * kPi / double(s.glass_light.photons);

  HostMesh mesh;
  for (size_t v = s.positions.size() - size_t(6 * stacks * slices - 6 * slices); v < s.positions.size(); ++v) {
    mesh.p.push_back(dvec3(s.positions[v]));
    mesh.n.push_back(dvec3(s.normals[v]));
  }
  ASSERT_EQ(mesh.p.size() % 3, 0u);
  // Photons from the light through the cone the ball's sphere fills, each I times the cone's solid angle over N.
  const double radii[] = {0.15, 0.3, 0.6, 1.2};
  const int photons = 20000;
  const double cos_cone = std::sqrt(1.0 - 1.0 / ((light_z - ball_z) * (light_z - ball_z)));
  const double host_flux = intensity * 2.0 * kPi * (1.0 - cos_cone) / photons;
  struct Landing {
    int photon;
    double distance, weight;  // from the axis below the light
  };
  std::vector<Landing> landings;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int k = 0; k < photons; ++k) {
    const double cos_t = 1.0 - uni(rng) * (1.0 - cos_cone), sin_t = std::sqrt(1.0 - cos_t * cos_t);
    const double phi = 2.0 * kPi * uni(rng);
    trace_through_glass(mesh, ior, dvec3(0.0, 0.0, light_z), dvec3(sin_t * std::cos(phi), sin_t * std::sin(phi), -cos_t),
                        1.0, 0, [&](double x, double y, double w) { landings.push_back({k, std::hypot(x, y), w}); });
  }
  // The host's mean irradiance between two distances from the axis, and its standard error over the photons.
  auto host_irradiance = [&](double from, double to, double* sigma) {
    from = std::max(from, 0.0);
    std::vector<double> per_photon(photons, 0.0);
    for (const Landing& l : landings)
      if (l.distance >= from && l.distance < to) per_photon[size_t(l.photon)] += l.weight;
    double sum = 0.0, squares = 0.0;
    for (double w : per_photon) sum += w, squares += w * w;
    const double area = kPi * (to * to - from * from);
    if (sigma) *sigma = std::sqrt(std::max(0.0, squares - sum * sum / photons)) * host_flux / area;
    return sum * host_flux / area;
  };
  ASSERT_GT(img.stats.scene.glass_caustic_photons, 10000u) << "the ball's photons";
  // Each photon spreads its light over its own level's radius (kernels/shared_types.h CausticMapLevel): the smallest
  // power of two of the smallest level's that holds its neighbours, so at most twice the radius of a disc that holds
  // them where the photons land as densely as the host's photons say, times the map's paths over the host's (both
  // aimed at the ball's sphere, kernels/light_guide.cl).
  const double neighbours = double(s.glass_light.neighbours);
  auto spread_at = [&](double distance) {
    const double from = std::max(distance - 0.05, 0.0), to = distance + 0.05;
    size_t landed = 0;
    for (const Landing& l : landings) landed += l.distance >= from && l.distance < to;
    const double density =
        double(landed) / (kPi * (to * to - from * from)) * (double(s.glass_light.photons) / photons);
    const double holding = density > 0.0 ? std::sqrt(neighbours / (kPi * density)) : INFINITY;
    return std::clamp(2.0 * holding, img.stats.scene.glass_caustic_radius, img.stats.scene.glass_caustic_largest_radius);
  };
  for (int r = 0; r < 4; ++r) {
    double host_sigma;
    const double host = host_irradiance(0.0, radii[r], &host_sigma);
    double measured = 0.0, squares = 0.0;
    size_t pixels = 0;
    for (size_t i = 0; i < img.triangle.size(); ++i) {
      const dvec3 x = position_of(img, i);
      if (img.triangle[i] < 0 || img.triangle[i] > 1 || std::hypot(x.x, x.y) >= radii[r]) continue;
      const double e = direct_of(img, i).y * kPi / double(kAlbedo.y);
      measured += e;
      squares += e * e;
      ++pixels;
    }
    ASSERT_GT(pixels, 30u);
    measured /= double(pixels);
    // The pixels' spread: each reads the photons within the map's radius of its point, and where that radius is
    // below the pixels' spacing they sample the focused light as much as the photons do.
    const double photon_sigma =
        std::sqrt(std::max(0.0, squares / double(pixels) - measured * measured) / double(pixels - 1));
    // A photon near the disc's edge spreads its light across it: at most the light of the ring one spread either
    // side of the edge, moved by less than the spread, over the disc.
    const double spread = spread_at(radii[r]);
    const double blur = host_irradiance(radii[r] - spread, radii[r] + spread, nullptr) * 2.0 * spread / radii[r];
    std::printf("glass ball, disc of radius %.2f: %.4f against the host's %.4f (sigma %.2e and %.2e, blur %.2e, %zu "
                "pixels, spread %.2e)\n",
                radii[r], measured, host, photon_sigma, host_sigma, blur, pixels, spread);
    EXPECT_NEAR(measured, host, 4.0 * std::hypot(photon_sigma, host_sigma) + blur) << "disc of radius " << radii[r];
  }
}

// The layers (kernels/brdf_layers.h) on the rough_floor: each pixel's direct light from the point light must be the
// extension's BRDF in double (tests/layers_reference.h) times the irradiance, within the float BRDF's 1e-4, the
// tabulated diffuse weight's error (floor_tolerance) and, under a sheen, the sheen albedo table's bilinear error
// (SheenAlbedo below bounds it by kSheenTableError where cos > 0.1) on what the sheen takes from the base. And the
// layer must matter: most pixels must differ from the bare base by more than their tolerance.
constexpr double kSheenTableError = 0.01;

void expect_layered_floor(const layers_reference::Layered& m, void (*layer)(Scene&)) {
  Scene s = rough_floor(float(m.roughness));
  layer(s);
  const RenderedImage img = render(s, 64, 0);
  layers_reference::Layered bare = m;
  bare.specular_color = {1.0, 1.0, 1.0};
  bare.clearcoat = 0.0;
  bare.sheen = {0.0, 0.0, 0.0};
  const double alpha = std::max(m.roughness * m.roughness, 1e-3);
  size_t checked = 0, distinguished = 0;
  for (size_t i = 0; i < img.triangle.size(); i += 4) {
    if (img.triangle[i] < 0) continue;
    const FloorPixel p = floor_pixel(s, img, i);
    const auto terms = layers_reference::ggx_albedo_terms(p.wo.z, alpha, 256);
    const double sheen_e = layers_reference::max3(m.sheen) > 0.0
                               ? std::min(layers_reference::sheen_albedo(p.wo.z, m.sheen_roughness, 96), 1.0)
                               : 0.0;
    const auto f = layers_reference::layered_brdf(m, p.wo, p.wi, terms, sheen_e);
    const auto f_bare = layers_reference::layered_brdf(bare, p.wo, p.wi, terms, 0.0);
    bool differs = false;
    for (size_t c = 0; c < 3; ++c) {
      const double expected = f[c] * p.irradiance, bare_value = f_bare[c] * p.irradiance;
      const double sheen_error = (p.wo.z < 0.1 ? 5.0 : 1.0) * kSheenTableError * layers_reference::max3(m.sheen);
      const double tolerance = floor_tolerance(p, expected) + sheen_error * bare_value;
      ASSERT_NEAR(direct_of(img, i)[c], expected, tolerance)
          << "pixel " << i << " channel " << c << " cos(theta_o) " << p.wo.z << " cos(theta_i) " << p.wi.z;
      differs |= std::fabs(bare_value - expected) > tolerance;
    }
    distinguished += differs;
    ++checked;
  }
  ASSERT_GT(checked, 400u);
  EXPECT_GT(distinguished, checked / 2) << "the layer must matter where it is tested";
}

// KHR_materials_clearcoat: a coat of roughness 0.3 over the rough dielectric. Planted: the coat's Fresnel taken at
// v.h instead of n.v (its weight and the base's), or the base left at full weight under it; each fails.
TEST(DirectLight, ClearcoatMatchesTheExtensionInDouble) {
  layers_reference::Layered m{{0.8, 0.8, 0.8}};
  m.roughness = 0.75;
  m.clearcoat = 1.0;
  m.clearcoat_roughness = 0.3;
  expect_layered_floor(m, [](Scene& s) {
    s.materials[0].clearcoat = 1.0f;
    s.materials[0].clearcoat_roughness = 0.3f;
  });
}

// KHR_materials_clearcoat's clearcoatNormalTexture: the coat's lobe and Fresnel follow its own map (one texel tilting
// it toward +x and -y), the base the interpolated normal. Planted: the coat about the interpolated normal; it fails.
TEST(DirectLight, ClearcoatFollowsItsOwnNormalMap) {
  layers_reference::Layered m{{0.8, 0.8, 0.8}};
  m.roughness = 0.75;
  m.clearcoat = 1.0;
  m.clearcoat_roughness = 0.3;
  m.coat_normal = brdf_reference::unit({205.0 / 127.5 - 1.0, 96.0 / 127.5 - 1.0, 214.0 / 127.5 - 1.0});
  expect_layered_floor(m, [](Scene& s) {
    s.materials[0].clearcoat = 1.0f;
    s.materials[0].clearcoat_roughness = 0.3f;
    SceneTexture t;
    t.width = t.height = 1;
    t.rgba = {205, 96, 214, 255};
    s.textures.push_back(t);
    s.materials[0].clearcoat_normal_texture = 0;
    s.tangents.assign(s.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  });
}

// The layers' textures multiply their factors: clearcoatTexture's R the coat's weight, sheenColorTexture's RGB (sRGB)
// the sheen's colour, one texel each. Planted: the coat texture's G read instead of R; it fails.
TEST(DirectLight, LayerTexturesScaleTheirFactors) {
  layers_reference::Layered m{{0.8, 0.8, 0.8}};
  m.roughness = 0.75;
  m.clearcoat = 200.0 / 255.0;
  m.clearcoat_roughness = 0.3;
  m.sheen = {srgb_to_linear(128.0 / 255.0), srgb_to_linear(64.0 / 255.0), srgb_to_linear(255.0 / 255.0)};
  m.sheen_roughness = 0.5;
  expect_layered_floor(m, [](Scene& s) {
    SceneTexture t;
    t.width = t.height = 1;
    t.rgba = {200, 30, 90, 255};
    s.textures.push_back(t);
    t.rgba = {128, 64, 255, 255};
    s.textures.push_back(t);
    s.materials[0].clearcoat = 1.0f;
    s.materials[0].clearcoat_texture = 0;
    s.materials[0].clearcoat_roughness = 0.3f;
    s.materials[0].sheen_color = glm::vec3(1.0f);
    s.materials[0].sheen_color_texture = 1;
    s.materials[0].sheen_roughness = 0.5f;
  });
}

// KHR_materials_sheen: a coloured sheen of roughness 0.5 over the rough dielectric, the base dimmed by
// 1 - max3(colour) E(n.v). Planted: the base left undimmed; it fails.
TEST(DirectLight, SheenMatchesTheExtensionInDouble) {
  layers_reference::Layered m{{0.8, 0.8, 0.8}};
  m.roughness = 0.75;
  m.sheen = {0.9, 0.5, 0.2};
  m.sheen_roughness = 0.5;
  expect_layered_floor(m, [](Scene& s) {
    s.materials[0].sheen_color = {0.9f, 0.5f, 0.2f};
    s.materials[0].sheen_roughness = 0.5f;
  });
}

// KHR_materials_specular's colour: F0 = min(0.04 colour, 1) per channel, the diffuse base weighed by what the
// strongest channel's lobe leaves. Planted: the colour ignored in the diffuse weight (0.04 kept there); it fails.
TEST(DirectLight, SpecularColourTintsTheDielectricsReflection) {
  layers_reference::Layered m{{0.8, 0.8, 0.8}};
  m.roughness = 0.75;
  m.specular_color = {1.5, 0.5, 12.0};
  expect_layered_floor(m, [](Scene& s) { s.materials[0].specular_color = {1.5f, 0.5f, 12.0f}; });
}

// The sheen lobe's albedo table (kernels/sheen_albedo_values.h, made by host/tables/make_sheen_albedo.cpp on a
// cosine-weighted grid) against layers_reference.h's quadrature in (theta, phi), read bilinearly as the kernels read
// it, at cell centres (the interpolation's worst) and nodes: within kSheenTableError for views above cos 0.1 and
// sheen roughness 0.2 or more, where the lobe is smooth enough for a 32 x 32 table (the albedo is taken as at most 1).
TEST(DirectLight, SheenAlbedoTableMatchesAnIndependentQuadrature) {
#define __constant const
#include "kernels/sheen_albedo_values.h"
#undef __constant
  const int n = SHEEN_ALBEDO_TABLE_SIZE;
  auto table = [&](double cos_o, double roughness) {
    const double x = cos_o * (n - 1), y = roughness * (n - 1);
    const int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int r, int c) { return double(sheen_albedo_values[r * n + c]); };
    const double bottom = at(y0, x0) * (1 - fx) + at(y0, x0 + 1) * fx, top = at(y0 + 1, x0) * (1 - fx) + at(y0 + 1, x0 + 1) * fx;
    return std::min(bottom * (1 - fy) + top * fy, 1.0);
  };
  double worst = 0.0;
  for (double roughness : {0.2, 0.35, 0.5, 0.75, 1.0})
    for (double cos_o : {0.1, 0.2, 0.35, 0.5, 0.7, 0.9, 1.0}) {
      for (double shift : {0.0, 0.5 / (n - 1)}) {
        const double c = std::min(cos_o + shift, 1.0), r = std::min(roughness + shift, 1.0);
        const double quadrature = std::min(layers_reference::sheen_albedo(c, r, 300), 1.0);
        worst = std::max(worst, std::fabs(table(c, r) - quadrature));
        ASSERT_NEAR(table(c, r), quadrature, kSheenTableError) << "cos " << c << " roughness " << r;
      }
    }
  std::printf("sheen albedo table: largest difference %.2e\n", worst);
}

}  // namespace
}  // namespace rcsplat
