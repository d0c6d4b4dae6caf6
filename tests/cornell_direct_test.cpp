// The built-in Cornell box's direct light on the device against a host reference written independently: Embree rays,
// double-precision shading, emitters sampled uniformly by area (the device samples by power, stratified), many samples.
// Compared per 6 x 6 region with a tolerance derived from both estimates' variances.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "bvh/embree_scene.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "test_support.h"
#include "util/ray_offset.h"

namespace rcsplat {
namespace {

using dvec3 = glm::dvec3;

struct ReferencePixel {
  int triangle = -1;
  dvec3 mean{0.0}, variance_of_one_sample{0.0};  // of the reflected direct radiance
};

std::vector<ReferencePixel> reference_direct(const Scene& s, const CameraParams& cam, int samples) {
  EmbreeScene embree(s.positions);
  std::vector<size_t> emitters;
  std::vector<double> cumulative_area;
  double total_area = 0.0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    if (glm::length(s.materials[s.triangle_material[t]].emission) == 0.0f) continue;
    const glm::vec3* v = &s.positions[3 * t];
    total_area += 0.5 * glm::length(glm::cross(dvec3(v[1] - v[0]), dvec3(v[2] - v[0])));
    emitters.push_back(t);
    cumulative_area.push_back(total_area);
  }
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<ReferencePixel> out(size_t(cam.width) * size_t(cam.height));
  dvec3 eye(cam.eye[0], cam.eye[1], cam.eye[2]), fwd(cam.forward[0], cam.forward[1], cam.forward[2]);
  dvec3 right(cam.right[0], cam.right[1], cam.right[2]), up(cam.up[0], cam.up[1], cam.up[2]);
  for (int py = 0; py < cam.height; ++py) {
    for (int px = 0; px < cam.width; ++px) {
      double sx = (2.0 * (px + 0.5) / cam.width - 1.0) * cam.tan_half_fov_y * cam.aspect;
      double sy = (1.0 - 2.0 * (py + 0.5) / cam.height) * cam.tan_half_fov_y;
      dvec3 dir = glm::normalize(fwd + sx * right + sy * up);
      EmbreeHit hit = embree.intersect(glm::vec3(eye), glm::vec3(dir), 0.0f, INFINITY);
      ReferencePixel& ref = out[size_t(py) * size_t(cam.width) + size_t(px)];
      ref.triangle = hit.prim;
      if (hit.prim < 0) continue;
      const glm::vec3* v = &s.positions[size_t(hit.prim) * 3];
      dvec3 x = (1.0 - hit.u - hit.v) * dvec3(v[0]) + double(hit.u) * dvec3(v[1]) + double(hit.v) * dvec3(v[2]);
      dvec3 n = glm::normalize(glm::cross(dvec3(v[1] - v[0]), dvec3(v[2] - v[0])));
      if (glm::dot(n, dir) > 0.0) n = -n;
      dvec3 albedo(s.materials[s.triangle_material[size_t(hit.prim)]].base_color);
      glm::vec3 origin = offset_ray_origin(glm::vec3(x), glm::vec3(n));
      dvec3 m1(0.0), m2(0.0);
      for (int k = 0; k < samples; ++k) {
        double pick = uni(rng) * total_area;
        size_t e = size_t(std::lower_bound(cumulative_area.begin(), cumulative_area.end(), pick) - cumulative_area.begin());
        e = std::min(e, emitters.size() - 1);
        const glm::vec3* w = &s.positions[emitters[e] * 3];
        double a = std::sqrt(uni(rng)), b = uni(rng);
        dvec3 y = (1.0 - a) * dvec3(w[0]) + a * (1.0 - b) * dvec3(w[1]) + a * b * dvec3(w[2]);
        dvec3 nl = glm::normalize(glm::cross(dvec3(w[1] - w[0]), dvec3(w[2] - w[0])));
        dvec3 to = y - x;
        double d2 = glm::dot(to, to);
        dvec3 wi = to / std::sqrt(d2);
        double cos_x = glm::dot(n, wi), cos_y = -glm::dot(nl, wi);
        dvec3 value(0.0);
        if (cos_x > 0.0 && cos_y > 0.0) {
          glm::vec3 target = offset_ray_origin(glm::vec3(y), glm::vec3(nl));
          if (!embree.occluded(origin, target - origin, 0.0f, 1.0f)) {
            dvec3 le(s.materials[s.triangle_material[emitters[e]]].emission);
            value = albedo / std::numbers::pi * le * (cos_x * cos_y / d2 * total_area);
          }
        }
        m1 += value;
        m2 += value * value;
      }
      ref.mean = m1 / double(samples);
      ref.variance_of_one_sample = glm::max(dvec3(0.0), m2 / double(samples) - ref.mean * ref.mean);
    }
  }
  return out;
}

TEST(CornellDirect, MatchesHostReferenceStatistically) {
  Scene scene = make_cornell_box();
  const int size = 48, region = 6, reference_samples = 1024;
  const unsigned device_samples = 16;
  RenderSettings settings = test::one_bounce_one_sample();
  settings.gi = GiMethod::none;
  settings.width = settings.height = size;
  settings.light_samples = device_samples;
  RenderedImage img = render(test::gpu(), scene, settings);
  CameraParams cam = camera_params(scene.cameras[0], size, size);
  std::vector<ReferencePixel> ref = reference_direct(scene, cam, reference_samples);

  size_t mismatched_hits = 0, regions = 0, lit_regions = 0;
  for (int ry = 0; ry < size; ry += region) {
    for (int rx = 0; rx < size; rx += region) {
      dvec3 device_sum(0.0), reference_sum(0.0), variance(0.0);
      int pixels = 0;
      for (int y = ry; y < ry + region; ++y)
        for (int x = rx; x < rx + region; ++x) {
          size_t i = size_t(y) * size + size_t(x);
          if (ref[i].triangle != img.triangle[i]) {  // a silhouette pixel whose primary rays parted: not comparable
            ++mismatched_hits;
            continue;
          }
          if (ref[i].triangle < 0) continue;
          ++pixels;
          for (int c = 0; c < 3; ++c) device_sum[c] += img.direct[3 * i + size_t(c)];
          reference_sum += ref[i].mean;
          // The device's stratified estimate has at most the variance of independent samples, and with one emissive
          // material choosing by power is choosing by area: the reference's per-sample variance stands in for both.
          variance += ref[i].variance_of_one_sample * (1.0 / device_samples + 1.0 / reference_samples);
        }
      if (pixels == 0) continue;
      ++regions;
      for (int c = 0; c < 3; ++c) {
        double sigma = std::sqrt(variance[c]);
        EXPECT_NEAR(device_sum[c] / pixels, reference_sum[c] / pixels, (5.0 * sigma + 1e-3 * reference_sum[c]) / pixels)
            << "region at (" << rx << ", " << ry << ") channel " << c;
      }
      lit_regions += reference_sum.y > 0.0;
    }
  }
  EXPECT_LT(mismatched_hits, size_t(size * size) / 100);
  EXPECT_GT(lit_regions, regions / 2);
}

}  // namespace
}  // namespace rcsplat
