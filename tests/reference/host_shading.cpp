#include "reference/host_shading.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "util/colour.h"
#include "util/ray_offset.h"

namespace rcsplat {
namespace {

using glm::dvec3;
constexpr double kPi = std::numbers::pi;

dvec3 load3(const float* v) { return dvec3(v[0], v[1], v[2]); }


int wrap(int i, int n, uint32_t mode) {
  if (mode == WRAP_CLAMP) return std::clamp(i, 0, n - 1);
  if (mode == WRAP_MIRROR) {
    int m = ((i % (2 * n)) + 2 * n) % (2 * n);
    return m < n ? m : 2 * n - 1 - m;
  }
  return ((i % n) + n) % n;
}

}  // namespace

bool HostShading::visible(const glm::vec3& from, const glm::vec3& to_offset, float tmax) const {
  return !embree_.occluded(from, to_offset, 0.0f, tmax);
}

glm::dvec3 HostShading::albedo(int triangle, double u, double v) const {
  const TriangleShading& t = scene_.triangles[size_t(triangle)];
  const Material& m = scene_.materials[t.material];
  dvec3 color = load3(m.base_color);
  if (m.base_color_texture >= 0) {
    double w = 1.0 - u - v;
    double tu = w * t.uv0[0] + u * t.uv1[0] + v * t.uv2[0], tv = w * t.uv0[1] + u * t.uv1[1] + v * t.uv2[1];
    const TextureInfo& info = scene_.textures[size_t(m.base_color_texture)];
    int width = int(info.width), height = int(info.height);
    uint32_t wrap_s = info.wrap & 255u, wrap_t = (info.wrap >> 8) & 255u;
    auto texel = [&](double x, double y) {  // the texel at integer coordinates, wrapped, in linear RGB
      uint32_t p = scene_.texels[info.first_texel + uint32_t(wrap(int(y), height, wrap_t)) * info.width +
                                 uint32_t(wrap(int(x), width, wrap_s))];
      return dvec3(srgb_to_linear((p & 255u) / 255.0), srgb_to_linear(((p >> 8) & 255u) / 255.0),
                   srgb_to_linear(((p >> 16) & 255u) / 255.0));
    };
    auto sane = [](double& x, double& y) {
      if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e8 || std::abs(y) > 1e8) x = y = 0.0;
    };
    if (info.wrap & TEXTURE_NEAREST) {
      double nx = std::floor(tu * width), ny = std::floor(tv * height);
      sane(nx, ny);
      color *= texel(nx, ny);
    } else {
      double fx = tu * width - 0.5, fy = tv * height - 0.5;
      sane(fx, fy);
      double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
      dvec3 sum(0.0);
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) sum += texel(x0 + dx, y0 + dy) * ((dx ? ax : 1.0 - ax) * (dy ? ay : 1.0 - ay));
      color *= sum;
    }
  }
  double w = 1.0 - u - v;  // vertex colours, from the same 10-bit values the device reads
  color *= w * dvec3(unpack_vertex_color(t.color[0])) + u * dvec3(unpack_vertex_color(t.color[1])) +
           v * dvec3(unpack_vertex_color(t.color[2]));
  return glm::clamp(color, 0.0, 1.0);
}

glm::dvec3 HostShading::direct_irradiance(const dvec3& p, const dvec3& n, const dvec3& ng, double u, double v) const {
  glm::vec3 origin = offset_ray_origin(glm::vec3(p), glm::vec3(ng));
  dvec3 e(0.0);
  for (const PunctualLight& l : scene_.lights) {
    dvec3 intensity = load3(l.intensity);
    if (l.type == LIGHT_DIRECTIONAL) {
      dvec3 wi = -load3(l.direction);
      double c = glm::dot(n, wi);
      if (c > 0.0 && glm::dot(ng, wi) > 0.0 && visible(origin, glm::vec3(wi), INFINITY)) e += intensity * c;
      continue;
    }
    dvec3 to = load3(l.position) - p;
    double d2 = glm::dot(to, to), d = std::sqrt(d2);
    if (!(d2 > 0.0)) continue;
    dvec3 wi = to / d;
    double c = glm::dot(n, wi);
    if (c <= 0.0 || glm::dot(ng, wi) <= 0.0) continue;
    double attenuation = 1.0 / d2;
    if (l.range > 0.0f) attenuation *= std::clamp(1.0 - std::pow(d / l.range, 4.0), 0.0, 1.0);
    if (l.type == LIGHT_SPOT) {
      double a = std::clamp(glm::dot(load3(l.direction), -wi) * l.spot_scale + l.spot_offset, 0.0, 1.0);
      attenuation *= a * a;
    }
    if (attenuation > 0.0 && visible(origin, glm::vec3(load3(l.position)) - origin, 1.0f)) e += intensity * attenuation * c;
  }
  if (!scene_.emitters.empty()) {
    // The emitter whose cumulative power interval holds u, then u reused within it (as kernels/lighting.h does).
    auto it = std::upper_bound(scene_.emitters.begin(), scene_.emitters.end(), float(u),
                               [](float x, const EmissiveTriangle& t) { return x < t.cdf; });
    const EmissiveTriangle& t = it == scene_.emitters.end() ? scene_.emitters.back() : *it;
    double u_in = std::clamp((u - (t.cdf - t.pdf_select)) / t.pdf_select, 0.0, 1.0 - 1e-7), su = std::sqrt(u_in);
    dvec3 e1 = load3(t.edge1), e2 = load3(t.edge2);
    dvec3 y = load3(t.v0) + su * (1.0 - v) * e1 + su * v * e2;
    dvec3 nl = glm::normalize(glm::cross(e1, e2));
    dvec3 to = y - p;
    double d2 = glm::dot(to, to);
    if (d2 > 0.0) {
      dvec3 wi = to / std::sqrt(d2);
      double cos_x = glm::dot(n, wi), cos_y = -glm::dot(nl, wi);
      if (emitter_double_sided(t)) cos_y = std::abs(cos_y);
      if (cos_x > 0.0 && cos_y > 0.0 && glm::dot(ng, wi) > 0.0) {
        glm::vec3 target = offset_ray_origin(glm::vec3(y), glm::vec3(glm::dot(nl, wi) < 0.0 ? nl : -nl));
        if (visible(origin, target - origin, 1.0f))
          e += load3(t.radiance) * (cos_x * cos_y * t.area / (d2 * t.pdf_select));
      }
    }
  }
  return e;
}

glm::dvec3 HostShading::bounce_radiance(const glm::vec3& origin, const dvec3& dir, double u, double v,
                                        double* distance) const {
  EmbreeHit hit = embree_.intersect(origin, glm::vec3(dir), 0.0f, INFINITY);
  if (hit.prim < 0) {
    *distance = std::numeric_limits<double>::infinity();
    return dvec3(0.0);
  }
  *distance = hit.t;
  const TriangleShading& t = scene_.triangles[size_t(hit.prim)];
  double w = 1.0 - hit.u - hit.v;
  dvec3 x = w * load3(t.v0) + double(hit.u) * load3(t.v1) + double(hit.v) * load3(t.v2);
  dvec3 ng = load3(t.geometric_normal);
  dvec3 ns = w * load3(t.normal0) + double(hit.u) * load3(t.normal1) + double(hit.v) * load3(t.normal2);
  ns = glm::length(ns) > 0.0 ? glm::normalize(ns) : ng;
  if (glm::dot(ng, dir) > 0.0) {
    ng = -ng;
    ns = -ns;
  }
  if (glm::dot(ns, ng) <= 0.0) ns = ng;
  dvec3 result = albedo(hit.prim, hit.u, hit.v) / kPi * direct_irradiance(x, ns, ng, u, v);
  return std::isfinite(result.x + result.y + result.z) ? result : dvec3(0.0);
}

}  // namespace rcsplat
