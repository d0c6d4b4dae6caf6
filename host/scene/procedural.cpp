#include "scene/procedural.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace rcsplat {
namespace {

void add_box(Scene& s, const glm::vec3& center, const glm::vec3& half, float angle, uint32_t material) {
  float c = std::cos(angle), sn = std::sin(angle);
  auto corner = [&](int i) {
    glm::vec3 local((i & 1 ? 1.0f : -1.0f) * half.x, (i & 2 ? 1.0f : -1.0f) * half.y, (i & 4 ? 1.0f : -1.0f) * half.z);
    return center + glm::vec3(c * local.x - sn * local.z, local.y, sn * local.x + c * local.z);
  };
  // Each face as corner indices, counter-clockwise from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    s.add_triangle(corner(f[0]), corner(f[1]), corner(f[2]), material);
    s.add_triangle(corner(f[0]), corner(f[2]), corner(f[3]), material);
  }
}

}  // namespace

Scene make_box_room(int boxes, uint32_t seed) {
  Scene s;
  s.source = "generated room with " + std::to_string(boxes) + " boxes";
  s.materials.push_back({"grey", {0.6f, 0.6f, 0.6f, 1.0f}, -1, {0, 0, 0}, false});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  // The room: an inward-facing box 20 x 10 x 20.
  add_box(s, glm::vec3(0, 5, 0), glm::vec3(10, 5, 10), 0.0f, 0);
  for (size_t t = 0; t < s.triangle_count(); ++t) std::swap(s.positions[3 * t + 1], s.positions[3 * t + 2]);
  for (glm::vec3& n : s.normals) n = -n;
  for (int b = 0; b < boxes; ++b) {
    glm::vec3 half(0.05f + 0.4f * uni(rng), 0.05f + 0.6f * uni(rng), 0.05f + 0.4f * uni(rng));
    glm::vec3 center(-9.0f + 18.0f * uni(rng), half.y + 6.0f * uni(rng) * uni(rng), -9.0f + 18.0f * uni(rng));
    add_box(s, center, half, 6.2831853f * uni(rng), 0);
  }
  SceneCamera cam;
  cam.eye = glm::vec3(-8.5f, 4.0f, -8.5f);
  cam.target = glm::vec3(0.0f, 1.5f, 0.0f);
  cam.yfov = 1.0f;
  cam.aspect = 4.0f / 3.0f;
  s.cameras.push_back(cam);
  SceneLight light;
  light.position = glm::vec3(0.0f, 9.0f, 0.0f);
  light.intensity = glm::vec3(200.0f);
  s.lights.push_back(light);
  return s;
}

Scene make_icosphere(int subdivisions, float radius, float bump) {
  // Icosahedron, subdivided with shared midpoints so that neighbouring triangles share exact vertex positions.
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<glm::ivec3> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                               {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                               {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (glm::vec3& p : v) p = glm::normalize(p);
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      std::pair<int, int> key(std::min(a, b), std::max(a, b));
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back(glm::normalize(v[size_t(a)] + v[size_t(b)]));
      return midpoint[key] = int(v.size() - 1);
    };
    std::vector<glm::ivec3> next;
    for (const glm::ivec3& tri : f) {
      int ab = mid(tri.x, tri.y), bc = mid(tri.y, tri.z), ca = mid(tri.z, tri.x);
      next.push_back({tri.x, ab, ca});
      next.push_back({tri.y, bc, ab});
      next.push_back({tri.z, ca, bc});
      next.push_back({ab, bc, ca});
    }
    f.swap(next);
  }
  std::vector<glm::vec3> radial = v;
  for (glm::vec3& p : v) p *= radius * (1.0f + bump * std::sin(7.0f * p.x) * std::sin(5.0f * p.y) * std::sin(6.0f * p.z));
  Scene s;
  s.source = bump != 0.0f ? "generated bumpy sphere" : "generated sphere";
  s.materials.push_back({"grey", {0.7f, 0.7f, 0.7f, 1.0f}, -1, {0, 0, 0}, false});
  for (const glm::ivec3& tri : f) {
    s.add_triangle(v[size_t(tri.x)], v[size_t(tri.y)], v[size_t(tri.z)], 0);
    if (bump == 0.0f)  // a smooth sphere: radial vertex normals
      for (int k = 0; k < 3; ++k) s.normals[s.normals.size() - 3 + size_t(k)] = radial[size_t(tri[k])];
  }
  SceneCamera cam;
  cam.eye = glm::vec3(0.0f, 0.0f, 3.0f * radius);
  cam.target = glm::vec3(0.0f);
  s.cameras.push_back(cam);
  return s;
}

Scene make_bumpy_sphere(int subdivisions, float radius) { return make_icosphere(subdivisions, radius, 0.08f); }

}  // namespace rcsplat
