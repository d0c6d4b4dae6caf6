#include "bench/ray_sets.h"

#include <cmath>
#include <random>

#include "render/camera.h"
#include "util/ray_offset.h"

namespace rcsplat {
namespace {

glm::vec3 cosine_direction(const glm::vec3& n, float u1, float u2) {
  glm::vec3 t, b;
  tangent_frame(n, &t, &b);  // the kernels' frame (kernels/host_device.h)
  float r = std::sqrt(u1), phi = 6.2831853f * u2;
  return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
}

RayDesc make_ray(const SurfaceSample& s, const glm::vec3& dir) {
  RayDesc r{};
  glm::vec3 o = offset_ray_origin(s.position, s.normal);
  for (int i = 0; i < 3; ++i) {
    r.origin[i] = o[i];
    r.direction[i] = dir[i];
  }
  r.tmin = 0.0f;
  r.tmax = INFINITY;
  return r;
}

}  // namespace

std::vector<SurfaceSample> camera_visible_points(const Scene& scene, const EmbreeScene& embree, size_t count,
                                                 uint32_t seed) {
  SceneCamera cam = scene.cameras.empty() ? SceneCamera{} : scene.cameras.front();
  int width = 1024, height = 0;
  resolve_resolution(cam, width, height);
  CameraParams p = camera_params(cam, width, height);
  glm::vec3 eye(p.eye[0], p.eye[1], p.eye[2]), fwd(p.forward[0], p.forward[1], p.forward[2]);
  glm::vec3 right(p.right[0], p.right[1], p.right[2]), up(p.up[0], p.up[1], p.up[2]);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::vector<SurfaceSample> points;
  points.reserve(count);
  for (size_t attempt = 0; points.size() < count && attempt < count * 20; ++attempt) {
    float sx = (2.0f * uni(rng) - 1.0f) * p.tan_half_fov_y * p.aspect;
    float sy = (2.0f * uni(rng) - 1.0f) * p.tan_half_fov_y;
    glm::vec3 dir = glm::normalize(fwd + sx * right + sy * up);
    EmbreeHit h = embree.intersect(eye, dir, 0.0f, INFINITY);
    if (h.prim < 0) continue;
    const glm::vec3* v = &scene.positions[size_t(h.prim) * 3];
    glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
    if (glm::dot(n, dir) > 0.0f) n = -n;
    // From the barycentrics, not eye + t * dir, whose rounding grows with the distance travelled.
    glm::vec3 position = (1.0f - h.u - h.v) * v[0] + h.u * v[1] + h.v * v[2];
    points.push_back({position, n});
  }
  return points;
}

std::vector<RayDesc> incoherent_hemisphere_rays(const std::vector<SurfaceSample>& points, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::vector<RayDesc> rays;
  rays.reserve(points.size());
  for (const SurfaceSample& s : points) rays.push_back(make_ray(s, cosine_direction(s.normal, uni(rng), uni(rng))));
  return rays;
}

std::vector<RayDesc> record_hemisphere_rays(const std::vector<SurfaceSample>& points, int strata, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::vector<RayDesc> rays;
  rays.reserve(points.size() * size_t(strata * strata));
  for (const SurfaceSample& s : points)
    for (int j = 0; j < strata; ++j)
      for (int k = 0; k < strata; ++k)
        rays.push_back(make_ray(s, cosine_direction(s.normal, (float(j) + uni(rng)) / float(strata),
                                                    (float(k) + uni(rng)) / float(strata))));
  return rays;
}

}  // namespace rcsplat
