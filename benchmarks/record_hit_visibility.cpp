// Would a second cache pass work for --bounces 2 and more (issue 11 part 3)? Its records would see the first pass's
// indirect light where a record's ray lands, but records exist only on surfaces the camera sees. This measures, for
// cosine-distributed rays from the visible surface (as a record casts them), the share whose hit the camera sees: in
// the frame, and not hidden (a ray from the eye reaches it first). Hits outside that share would need records placed
// off-screen.
//   build/benchmarks/record_hit_visibility [SCENE.gltf] [WIDTH HEIGHT] [RAYS]
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bvh/bvh8.h"
#include "cl/device_info.h"
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/ray_cast_pass.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "scene/gltf_loader.h"
#include "util/ray_offset.h"

using namespace rcsplat;

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "";
  const int width = argc > 3 ? std::atoi(argv[2]) : 256, height = argc > 3 ? std::atoi(argv[3]) : 192;
  const size_t rays = argc > 4 ? size_t(std::atol(argv[4])) : 200000;
  Scene scene = path.empty() ? make_cornell_box() : load_gltf(path);
  GpuContext gpu(select_device(""));
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.gi = GiMethod::none;
  settings.light_samples = 0;
  const RenderedImage frame = render(gpu, scene, settings);
  const SceneCamera camera = choose_camera(scene, 0, {});
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up)), up = glm::cross(right, forward);
  const float tan_y = std::tan(0.5f * camera.yfov), tan_x = tan_y * float(frame.width) / float(frame.height);

  // World-space rays from random visible pixels, cosine-distributed about the shading normal.
  std::vector<size_t> visible;
  for (size_t i = 0; i < frame.triangle.size(); ++i)
    if (frame.triangle[i] >= 0) visible.push_back(i);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<RayDesc> from_surface;
  std::vector<glm::vec3> origins, directions;
  for (size_t r = 0; r < rays && !visible.empty(); ++r) {
    size_t i = visible[size_t(u(rng) * float(visible.size())) % visible.size()];
    glm::vec3 p(frame.position[3 * i], frame.position[3 * i + 1], frame.position[3 * i + 2]);
    glm::vec3 n(frame.normal[3 * i], frame.normal[3 * i + 1], frame.normal[3 * i + 2]);
    if (glm::dot(n, camera.eye - p) < 0.0f) n = -n;  // the side the camera sees
    glm::vec3 t = glm::normalize(std::fabs(n.x) > 0.5f ? glm::cross(n, glm::vec3(0, 1, 0)) : glm::cross(n, glm::vec3(1, 0, 0)));
    glm::vec3 b = glm::cross(n, t);
    float r1 = u(rng), phi = 6.2831853f * u(rng), s = std::sqrt(r1);
    glm::vec3 d = s * std::cos(phi) * t + s * std::sin(phi) * b + std::sqrt(1.0f - r1) * n;
    glm::vec3 o = offset_ray_origin(p, n);
    origins.push_back(o);
    directions.push_back(d);
    from_surface.push_back({{o.x, o.y, o.z}, 0.0f, {d.x, d.y, d.z}, 1e30f});
  }
  Bvh8 bvh = build_bvh8(scene.positions);
  DeviceScene device(gpu, scene, bvh);
  RayCastPass caster(gpu, device);
  caster.set_rays(from_surface);
  caster.cast_closest();
  std::vector<HitDesc> hits = caster.closest_hits();

  // From the eye toward each hit: visible when in the frame and nothing nearer lies on the way.
  std::vector<RayDesc> from_eye;
  std::vector<float> distance;
  size_t landed = 0, in_frame = 0;
  for (size_t r = 0; r < hits.size(); ++r) {
    if (hits[r].prim < 0) continue;
    ++landed;
    glm::vec3 h = origins[r] + hits[r].t * directions[r], d = h - camera.eye;
    float z = glm::dot(d, forward);
    if (!(z > 0.0f) || std::fabs(glm::dot(d, right)) > tan_x * z || std::fabs(glm::dot(d, up)) > tan_y * z) continue;
    ++in_frame;
    float l = glm::length(d);
    from_eye.push_back({{camera.eye.x, camera.eye.y, camera.eye.z}, 0.0f, {d.x / l, d.y / l, d.z / l}, 1e30f});
    distance.push_back(l);
  }
  caster.set_rays(from_eye);
  caster.cast_closest();
  std::vector<HitDesc> seen = caster.closest_hits();
  size_t visible_hits = 0;
  for (size_t r = 0; r < seen.size(); ++r)
    visible_hits += seen[r].prim >= 0 && seen[r].t >= distance[r] * (1.0f - 1e-3f);
  std::printf("%s %d x %d: %zu rays from visible surfaces, %zu landed; in the frame %.1f%%, seen by the camera %.1f%%\n",
              path.empty() ? "built-in Cornell box" : path.c_str(), frame.width, frame.height, hits.size(), landed,
              100.0 * double(in_frame) / double(std::max<size_t>(landed, 1)),
              100.0 * double(visible_hits) / double(std::max<size_t>(landed, 1)));
  return 0;
}
