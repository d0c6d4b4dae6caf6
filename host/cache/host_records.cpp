#include "cache/host_records.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "kernels/counter_random.h"
#include "util/ray_offset.h"

namespace rcsplat {
namespace {

using glm::dvec3;
constexpr double kPi = std::numbers::pi;

void add_outer(std::array<dvec3, 3>& g, const dvec3& direction, const dvec3& value) {
  for (int a = 0; a < 3; ++a) g[size_t(a)] += direction[a] * value;
}

// Per channel, scales the gradient so that its length is at most limit.
void bound(std::array<dvec3, 3>& g, const dvec3& limit) {
  for (int c = 0; c < 3; ++c) {
    double len = std::sqrt(g[0][c] * g[0][c] + g[1][c] * g[1][c] + g[2][c] * g[2][c]);
    double s = len > limit[c] ? limit[c] / len : 1.0;
    for (auto& row : g) row[c] = std::isfinite(row[c] * s) ? row[c] * s : 0.0;
  }
}

}  // namespace

HostRecord compute_host_record(const HostShading& shading, const glm::vec3& pf, const glm::vec3& nf,
                               const glm::vec3& ngf, uint32_t pixel, double pixel_size, const HemisphereParams& hp) {
  const int M = int(hp.theta_strata), N = int(hp.phi_strata);
  dvec3 p(pf), n(nf), ng(ngf);
  glm::vec3 origin = offset_ray_origin(pf, ngf);
  // The same frame as kernels/bounce.h tangent_frame (Duff et al.), so the same numbers give the same rays.
  double sign = n.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sign + n.z), c = n.x * n.y * a;
  dvec3 t(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x), b(c, sign + n.y * n.y * a, -n.y);
  uint32_t key = hash_u32(pixel ^ hash_u32(hp.seed));

  std::vector<dvec3> L(size_t(M * N));
  std::vector<double> r(size_t(M * N));
  HostRecord rec;
  for (int j = 0; j < M; ++j)
    for (int k = 0; k < N; ++k) {
      uint32_t s = uint32_t(j * N + k);
      double sin2 = (j + double(random01(key, s, 0))) / M;
      double phi = 2.0 * kPi * (k + double(random01(key, s, 1))) / N;
      double st = std::sqrt(sin2), ct = std::sqrt(1.0 - sin2);
      dvec3 dir = std::cos(phi) * st * t + std::sin(phi) * st * b + ct * n;
      double dist = std::numeric_limits<double>::infinity();
      dvec3 l(0.0);
      if (glm::dot(dir, ng) > 0.0) {
        l = shading.bounce_radiance(origin, glm::normalize(dir), random01(key, s, 2), random01(key, s, 3), &dist);
        ++rec.rays;
      }
      L[size_t(s)] = l;
      r[size_t(s)] = dist;
    }
  auto at = [&](int j, int k) { return size_t(j * N + ((k % N) + N) % N); };

  dvec3 e(0.0);
  double inverse_distances = 0.0;
  for (size_t s = 0; s < L.size(); ++s) {
    e += L[s];
    inverse_distances += 1.0 / r[s];
  }
  e *= kPi / (M * N);
  for (int k = 0; k < N; ++k) {
    double phi_mid = 2.0 * kPi * (k + 0.5) / N, phi_lo = 2.0 * kPi * k / N;
    dvec3 u_mid = std::cos(phi_mid) * t + std::sin(phi_mid) * b, v_mid = -std::sin(phi_mid) * t + std::cos(phi_mid) * b;
    dvec3 v_lo = -std::sin(phi_lo) * t + std::cos(phi_lo) * b;
    dvec3 rotation(0.0);
    for (int j = 0; j < M; ++j) {
      double cos_lo = std::sqrt(1.0 - double(j) / M);
      // Rotation: L sin(theta) v(phi) integrated over the stratum, L taken constant in it.
      double th_lo = std::asin(std::sqrt(double(j) / M)), th_hi = std::asin(std::sqrt(double(j + 1) / M));
      rotation += ((th_hi - th_lo) / 2.0 - (std::sin(2.0 * th_hi) - std::sin(2.0 * th_lo)) / 4.0) * L[at(j, k)];
      // Wall at phi_k- between columns k - 1 and k: content crosses it at angular speed 1 / (r sin(theta)), weighted
      // by the projected solid angle cos(theta) sin(theta) dtheta, hence the integral of cos(theta) over the stratum.
      double wall = std::sqrt(double(j + 1) / M) - std::sqrt(double(j) / M);
      add_outer(rec.grad_translation, v_lo, wall / std::min(r[at(j, k)], r[at(j, k - 1)]) * (L[at(j, k)] - L[at(j, k - 1)]));
      // Wall at theta_j- between rows j - 1 and j.
      if (j > 0) {
        double sin_lo = std::sqrt(double(j) / M);
        double coef = 2.0 * kPi / N * sin_lo * cos_lo * cos_lo / std::min(r[at(j, k)], r[at(j - 1, k)]);
        add_outer(rec.grad_translation, u_mid, coef * (L[at(j, k)] - L[at(j - 1, k)]));
      }
    }
    add_outer(rec.grad_rotation, v_mid, rotation * (2.0 * std::sin(kPi / N)));
  }

  rec.position = p;
  rec.normal = n;
  rec.irradiance = std::isfinite(e.x + e.y + e.z) ? e : dvec3(0.0);
  rec.harmonic_distance = double(M * N) / inverse_distances;
  rec.pixel_size = pixel_size;
  rec.pixel = pixel;
  rec.radius = std::clamp(rec.harmonic_distance, hp.min_radius_pixels * pixel_size, hp.max_radius_pixels * pixel_size);
  bound(rec.grad_translation, rec.irradiance / rec.radius);
  bound(rec.grad_rotation, rec.irradiance);
  return rec;
}

CacheRecord to_cache_record(const HostRecord& r) {
  CacheRecord out{};
  for (int i = 0; i < 3; ++i) {
    out.position[i] = float(r.position[i]);
    out.normal[i] = float(r.normal[i]);
    out.irradiance[i] = float(r.irradiance[i]);
    for (int c = 0; c < 3; ++c) {
      out.grad_translation[3 * i + c] = float(r.grad_translation[size_t(i)][c]);
      out.grad_rotation[3 * i + c] = float(r.grad_rotation[size_t(i)][c]);
    }
  }
  out.radius = float(r.radius);
  out.pixel = int32_t(r.pixel);
  out.pixel_size = float(r.pixel_size);
  out.harmonic_distance = float(r.harmonic_distance);
  return out;
}

}  // namespace rcsplat
