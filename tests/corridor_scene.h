// Issue 10's small bright indirect source: a corridor lit only by a patch under a strong spot, and its exact indirect
// light. Shared by the tests and benchmarks/hard_case_corridor.cpp; needs neither GoogleTest nor a device.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "box_room.h"
#include "brdf_reference.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace rcsplat::test {

// A closed corridor (10 x 2 x 2.5 m, grey) lit by one 1e6 cd spot whose cone reaches only a disc of radius 0.25 m
// on the floor near the far end: every wall, and the ceiling, is lit only by the light that patch reflects. Cosine
// sampling of a record's hemisphere finds the patch in some records and misses it in others: each one that finds it
// becomes a bright disc on the walls (the blotches of issue 10). benchmarks/hard_case_corridor.cpp renders and times
// it against its exact indirect light.
// With metal_wall_roughness > 0 the walls and ceiling are metal of that roughness instead of grey Lambertian: at
// HSH_MIN_ROUGHNESS .. ROUGH_METAL_MIN_ROUGHNESS their light is radiance-cached (kernels/hsh_records.cl), and each
// record that sees the disc holds its bright reflection.
inline Scene bright_patch_corridor(float metal_wall_roughness = 0.0f) {
  // The camera at the near end, z = 0.
  Scene s = grey_box_room("bright-patch corridor", {-1.0f, 0.0f, -10.0f}, {1.0f, 2.5f, 0.0f});
  if (metal_wall_roughness > 0.0f) {
    s.materials.back().metallic = 1.0f;
    s.materials.back().specular = 1.0f;
    s.materials.back().roughness = metal_wall_roughness;
  }
  SceneLight spot;
  spot.type = LightType::spot;
  spot.position = {0.4f, 2.4f, -7.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.intensity = glm::vec3(1e6f);
  spot.inner_cone = 0.0f;
  spot.outer_cone = std::atan(0.25f / 2.4f);
  s.lights.push_back(spot);
  add_camera(s, {0.0f, 1.2f, -0.2f}, {0.0f, 1.2f, -5.0f}, 1.0f);
  return s;
}

// The corridor's indirect light in double precision, without sampling: the room is convex, so every point sees all of
// the lit disc, and the one-bounce radiance it receives is the integral over that disc of (floor albedo / pi) E(x)
// cos cos' / d^2, E the spot's irradiance with glTF's smooth cone falloff. Midpoint quadrature, polar (the integrand
// is smooth on the disc); a Lambertian pixel's value is its albedo / pi times that irradiance at its G-buffer point,
// a glossy pixel's the same sum with its BRDF (tests/brdf_reference.h) toward the camera in place of albedo / pi.
inline std::vector<float> corridor_indirect_by_quadrature(const Scene& corridor, const RenderedImage& img) {
  const SceneLight& spot = corridor.lights[0];
  const glm::dvec3 light(spot.position);
  const double height = light.y, intensity = spot.intensity.x, floor_albedo = corridor.materials[0].base_color.x;
  const double cos_outer = std::cos(double(spot.outer_cone)), scale = 1.0 / (1.0 - cos_outer);
  const double disc_radius = height * std::tan(double(spot.outer_cone));
  const int rings = 64, sectors = 128;
  struct Patch { glm::dvec3 x; double radiance_area; };  // a quadrature cell: its centre and L dA
  std::vector<Patch> cells;
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < sectors; ++k) {
      double r = (i + 0.5) / rings * disc_radius, phi = (k + 0.5) / sectors * 2.0 * M_PI;
      double dr = disc_radius / rings, dphi = 2.0 * M_PI / sectors;
      double d2 = height * height + r * r, cos_light = height / std::sqrt(d2);
      double falloff = std::clamp((cos_light - cos_outer) * scale, 0.0, 1.0);
      double irradiance = intensity * falloff * falloff * cos_light / d2;  // cos at the floor = cos at the light
      cells.push_back({glm::dvec3(light.x + r * std::cos(phi), 0.0, light.z + r * std::sin(phi)),
                       floor_albedo / M_PI * irradiance * r * dr * dphi});
    }
  const glm::vec3 eye = corridor.cameras[0].eye;
  const size_t pixels = size_t(img.width) * size_t(img.height);
  std::vector<float> indirect(pixels * 3, 0.0f);
  for (size_t p = 0; p < pixels; ++p) {
    if (img.triangle[p] < 0) continue;
    glm::dvec3 at(img.position[3 * p], img.position[3 * p + 1], img.position[3 * p + 2]);
    glm::dvec3 n(img.normal[3 * p], img.normal[3 * p + 1], img.normal[3 * p + 2]);
    const SceneMaterial& m = corridor.materials[corridor.triangle_material[size_t(img.triangle[p])]];
    const bool lambertian = !(m.metallic > 0.0f) && !(m.specular > 0.0f);
    // The pixel's frame: n, and the view direction's component along the surface as x.
    const glm::dvec3 to_eye = glm::normalize(glm::dvec3(eye) - at);
    glm::dvec3 x = to_eye - glm::dot(to_eye, n) * n;
    if (!(glm::length(x) > 1e-9)) x = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) - n.x * n : glm::dvec3(0, 1, 0) - n.y * n;
    x = glm::normalize(x);
    const glm::dvec3 y = glm::cross(n, x);
    const brdf_reference::Material brdf{{m.base_color.x, m.base_color.y, m.base_color.z}, m.metallic, m.roughness,
                                        m.specular};
    const brdf_reference::Vec wo{glm::dot(to_eye, x), 0.0, glm::dot(to_eye, n)};
    double radiance[3] = {0.0, 0.0, 0.0};
    for (const Patch& c : cells) {
      glm::dvec3 to = c.x - at;
      double d2 = glm::dot(to, to), d = std::sqrt(d2);
      double cos_here = glm::dot(n, to) / d, cos_there = -to.y / d;  // the floor faces +y
      if (!(cos_here > 0.0 && cos_there > 0.0)) continue;
      double e = c.radiance_area * cos_here * cos_there / d2;
      if (lambertian) {
        for (int ch = 0; ch < 3; ++ch) radiance[ch] += img.albedo[3 * p + ch] / M_PI * e;
        continue;
      }
      const brdf_reference::Vec wi{glm::dot(to, x) / d, glm::dot(to, y) / d, cos_here};
      std::array<double, 3> f = brdf_reference::reference_brdf(brdf, wo, wi, true, true);
      for (int ch = 0; ch < 3; ++ch) radiance[ch] += f[size_t(ch)] * e;
    }
    for (int ch = 0; ch < 3; ++ch) indirect[3 * p + ch] = float(radiance[ch]);
  }
  return indirect;
}

}  // namespace rcsplat::test
