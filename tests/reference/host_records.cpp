#include "reference/host_records.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "kernels/counter_random.h"
#include "kernels/low_discrepancy.h"
#include "util/colour.h"
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

// The frame kernels/host_device.h tangent_frame builds (Duff et al.), so the same numbers give the same rays.
void frame_around(const dvec3& n, dvec3& t, dvec3& b) {
  double sign = n.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sign + n.z), c = n.x * n.y * a;
  t = dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = dvec3(c, sign + n.y * n.y * a, -n.y);
}

dvec3 load3(const float* v) { return dvec3(v[0], v[1], v[2]); }

// Lambert's form factor of the polygon seen from x with normal n: 1/(2 pi) sum_edges angle * n.(r_i x r_i+1)/|..|,
// signed by the polygon's winding.
double polygon_form_factor(const std::vector<dvec3>& polygon, const dvec3& x, const dvec3& n) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    dvec3 ra = polygon[i] - x, rb = polygon[(i + 1) % polygon.size()] - x, c = glm::cross(ra, rb);
    double len = glm::length(c);
    if (len > 0.0) sum += std::atan2(len, glm::dot(ra, rb)) * glm::dot(n, c) / len;
  }
  return sum / (2.0 * kPi);
}

// The largest curvature (eigenvalue magnitude) of the record's relative irradiance along its tangent plane, for the
// occlusion-Hessian radius: the mesh of kernels/records.cl relative_irradiance_hessian (hit points, values, the
// farthest vertex's value per triangle, the cap), its irradiance sum_polygons value * form factor evaluated exactly at
// offsets of the receiver, and the Hessian by central differences (not the kernel's closed form per edge).
double relative_irradiance_curvature(const std::vector<dvec3>& dirs, const std::vector<dvec3>& L,
                                     const std::vector<double>& r, int M, int N, const dvec3& n, const dvec3& t,
                                     const dvec3& b, double near, double far) {
  double sum = 0.0;
  for (const dvec3& l : L) sum += luminance(l);
  double scale = 0.0, floor = 1.0;
  if (sum > 0.0 && std::isfinite(sum)) {
    scale = 0.99 * M * N / sum;
    floor = 0.01;
  }
  // The mesh: rows and columns of the strata taken every step-th (4 of each where they divide evenly), the rows
  // ending at the last; kernels/records.cl hessian_mesh.
  auto step_of = [](int strata) {
    int step = strata / 4;
    return step > 1 && strata % step == 0 ? step : 1;
  };
  const int row_step = step_of(M), column_step = step_of(N), rows = M / row_step, columns = N / column_step;
  const int row_first = M - 1 - (rows - 1) * row_step;
  auto at = [&](int j, int k) {
    return size_t((row_first + j * row_step) * N + ((k % columns) + columns) % columns * column_step);
  };
  std::vector<dvec3> point(L.size());
  std::vector<double> dist(L.size()), value(L.size());
  for (size_t s = 0; s < L.size(); ++s) {
    dist[s] = std::clamp(r[s], near, far);
    point[s] = dirs[s] * dist[s];
    value[s] = luminance(L[s]) * scale + floor;
  }
  std::vector<std::vector<dvec3>> polygons;
  std::vector<double> values;
  std::vector<dvec3> cap;
  double cap_value = 0.0;
  for (int k = 0; k < columns; ++k) {
    cap.push_back(point[at(0, k)]);
    cap_value += value[at(0, k)] / columns;
  }
  polygons.push_back(cap);
  values.push_back(cap_value);
  for (int j = 0; j + 1 < rows; ++j)
    for (int k = 0; k < columns; ++k)
      for (auto tri : {std::array<size_t, 3>{at(j, k), at(j + 1, k), at(j, k + 1)},
                       std::array<size_t, 3>{at(j + 1, k + 1), at(j, k + 1), at(j + 1, k)}}) {
        size_t farthest = tri[0];
        for (size_t v : tri)
          if (dist[v] > dist[farthest]) farthest = v;
        polygons.push_back({point[tri[0]], point[tri[1]], point[tri[2]]});
        values.push_back(value[farthest]);
      }
  auto irradiance = [&](double dt, double db) {
    dvec3 x = dt * t + db * b;
    double e = 0.0;
    for (size_t i = 0; i < polygons.size(); ++i) e += values[i] * polygon_form_factor(polygons[i], x, n);
    return e;
  };
  double nearest = std::numeric_limits<double>::infinity();
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < columns; ++k) nearest = std::min(nearest, dist[at(j, k)]);
  double h = 1e-3 * nearest, e0 = irradiance(0, 0);
  double tt = (irradiance(h, 0) - 2.0 * e0 + irradiance(-h, 0)) / (h * h);
  double bb = (irradiance(0, h) - 2.0 * e0 + irradiance(0, -h)) / (h * h);
  double tb = (irradiance(h, h) - irradiance(h, -h) - irradiance(-h, h) + irradiance(-h, -h)) / (4.0 * h * h);
  return std::abs(0.5 * (tt + bb)) + std::hypot(0.5 * (tt - bb), tb);
}

// The cluster's flux leaving a disc toward p: Phi cos cos' / (pi d^2), visibility ignored, d at least the radius.
double promised_irradiance(const GuideCluster& g, const dvec3& p, const dvec3& n) {
  dvec3 to = load3(g.centre) - p;
  double radius = g.radius, d = std::sqrt(std::max(glm::dot(to, to), radius * radius));
  dvec3 axis = to / d, cn = load3(g.normal);
  double cos_here = std::clamp(glm::dot(axis, n) + radius / d, 0.0, 1.0);
  double cos_there = std::clamp(-glm::dot(cn, axis) + (1.0 - std::min(glm::length(cn), 1.0)) + radius / d, 0.0, 1.0);
  double flux = luminance(g.flux);
  return flux * cos_here * cos_there / (kPi * d * d);
}

}  // namespace

// The cones worth aiming at: at most GUIDE_MAX_STRATA strata of solid angle, at least GUIDE_MIN_SHARE of the
// irradiance all clusters promise, the point outside 1.5 r^2.
std::vector<HostGuideCone> host_guide_cones(const std::vector<GuideCluster>& guide, const dvec3& p, const dvec3& n,
                                            int strata) {
  std::vector<double> promise;
  double promised = 0.0;
  for (const GuideCluster& g : guide) promised += promise.emplace_back(promised_irradiance(g, p, n));
  std::vector<HostGuideCone> cones;
  double total = 0.0;
  for (size_t i = 0; i < guide.size(); ++i) {
    const GuideCluster& g = guide[i];
    double w = promise[i];
    dvec3 to = load3(g.centre) - p;
    double d2 = glm::dot(to, to), r2 = double(g.radius) * g.radius;
    if (!(w > 0.0) || w < double(GUIDE_MIN_SHARE) * promised || !(d2 > 1.5 * r2)) continue;
    HostGuideCone c;
    c.axis = to / std::sqrt(d2);
    c.cos_max = std::sqrt(1.0 - r2 / d2);
    c.solid_angle = 2.0 * kPi * (1.0 - c.cos_max);
    if (c.solid_angle > double(GUIDE_MAX_STRATA) * kPi / strata) continue;
    c.probability = w;
    total += w;
    cones.push_back(c);
  }
  // The GUIDE_MAX_CONES that promise most, the clusters' order kept among equals.
  std::stable_sort(cones.begin(), cones.end(),
                   [](const HostGuideCone& a, const HostGuideCone& b) { return a.probability > b.probability; });
  if (cones.size() > GUIDE_MAX_CONES) cones.resize(GUIDE_MAX_CONES);
  total = 0.0;
  for (const HostGuideCone& c : cones) total += c.probability;
  double running = 0.0;
  for (HostGuideCone& c : cones) {
    c.probability /= total;
    c.cdf = (running += c.probability);
  }
  return cones;
}

double host_guide_density(const std::vector<HostGuideCone>& cones, const dvec3& dir) {
  double pdf = 0.0;
  for (const HostGuideCone& c : cones)
    if (glm::dot(dir, c.axis) >= c.cos_max) pdf += c.probability / c.solid_angle;
  return pdf;
}

dvec3 host_guide_direction(const std::vector<HostGuideCone>& cones, double u, double v, double w) {
  size_t chosen = 0;
  while (chosen + 1 < cones.size() && u >= cones[chosen].cdf) ++chosen;
  const HostGuideCone& cone = cones[chosen];
  double one_minus_cos = v * (1.0 - cone.cos_max), phi = 2.0 * kPi * w;
  double cos_t = 1.0 - one_minus_cos, sin_t = std::sqrt(std::max(one_minus_cos * (2.0 - one_minus_cos), 0.0));
  dvec3 ct, cb;
  frame_around(cone.axis, ct, cb);
  return std::cos(phi) * sin_t * ct + std::sin(phi) * sin_t * cb + cos_t * cone.axis;
}


HostRecord compute_host_record(const HostShading& shading, const glm::vec3& pf, const glm::vec3& nf,
                               const glm::vec3& ngf, uint32_t pixel, double pixel_size, const HemisphereParams& hp,
                               const std::vector<GuideCluster>& guide) {
  const int M = int(hp.theta_strata), N = int(hp.phi_strata);
  dvec3 p(pf), n(nf), ng(ngf);
  glm::vec3 origin = offset_ray_origin(pf, ngf);
  dvec3 t, b;
  frame_around(n, t, b);
  uint32_t key = hash_u32(pixel ^ hash_u32(hp.seed));
  const std::vector<HostGuideCone> cones =
      hp.guide_rays ? host_guide_cones(guide, p, n, M * N) : std::vector<HostGuideCone>{};
  const double guided = cones.empty() ? 0.0 : double(hp.guide_rays), strata_density = M * N / kPi;

  std::vector<dvec3> L(size_t(M * N)), dirs(size_t(M * N));
  std::vector<double> r(size_t(M * N)), sin_theta(size_t(M * N));
  HostRecord rec;
  for (int j = 0; j < M; ++j)
    for (int k = 0; k < N; ++k) {
      uint32_t s = uint32_t(j * N + k);
      double sin2 = (j + double(random01(key, s, 0))) / M;
      double phi = 2.0 * kPi * (k + double(random01(key, s, 1))) / N;
      double st = std::sqrt(sin2), ct = std::sqrt(1.0 - sin2);
      sin_theta[size_t(s)] = st;
      dvec3 dir = std::cos(phi) * st * t + std::sin(phi) * st * b + ct * n;
      dirs[size_t(s)] = dir;
      double dist = std::numeric_limits<double>::infinity();
      dvec3 l(0.0);
      if (glm::dot(dir, ng) > 0.0) {
        l = shading.bounce_radiance(origin, glm::normalize(dir), random01(key, s, 2), random01(key, s, 3), &dist);
        ++rec.rays;
      }
      // Balance heuristic: the strata keep their density's share of the light.
      if (!cones.empty()) l *= strata_density * ct / (strata_density * ct + guided * host_guide_density(cones, dir));
      L[size_t(s)] = l;
      r[size_t(s)] = dist;
    }
  dvec3 e_guided(0.0);
  for (uint32_t g = 0; g < (cones.empty() ? 0u : hp.guide_rays); ++g) {
    uint32_t s = uint32_t(M * N) + g;
    float u, v, w;
    scrambled_sobol3(g, key, &u, &v, &w);
    dvec3 dir = host_guide_direction(cones, u, v, w);
    double cos_n = glm::dot(dir, n);
    if (cos_n <= 0.0 || glm::dot(dir, ng) <= 0.0) continue;
    double dist;
    dvec3 l = shading.bounce_radiance(origin, glm::normalize(dir), random01(key, s, 2), random01(key, s, 3), &dist);
    ++rec.rays;
    e_guided += l * cos_n / (strata_density * cos_n + guided * host_guide_density(cones, dir));
  }
  rec.strata_radiance = L;
  auto at = [&](int j, int k) { return size_t(j * N + ((k % N) + N) % N); };

  dvec3 e(0.0);
  double inverse_distances = 0.0;
  for (size_t s = 0; s < L.size(); ++s) {
    e += L[s];
    inverse_distances += 1.0 / r[s];
  }
  e = e * (kPi / (M * N)) + e_guided;
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

  // Horizon: a column's nearest occluder among its rays below 30 degrees of elevation (sin^2 theta >= 3/4), along the
  // tangent plane; a sector's, the nearest of its columns' (a column's centre azimuth decides its sector).
  std::array<double, RECORD_HORIZON_SECTORS> horizon;
  horizon.fill(std::numeric_limits<double>::infinity());
  for (int k = 0; k < N; ++k) {
    double column = std::numeric_limits<double>::infinity();
    for (int j = 0; j < M; ++j)
      if (double(j) / M >= 0.75) column = std::min(column, r[at(j, k)] * sin_theta[at(j, k)]);
    size_t sector = size_t(std::floor((k + 0.5) / N * RECORD_HORIZON_SECTORS)) % RECORD_HORIZON_SECTORS;
    horizon[sector] = std::min(horizon[sector], column);
  }
  for (size_t s = 0; s < horizon.size(); ++s)
    rec.horizon[s] = std::max(horizon[s], 0.5 * pixel_size);

  rec.position = p;
  rec.normal = n;
  rec.irradiance = std::isfinite(e.x + e.y + e.z) ? e : dvec3(0.0);
  rec.harmonic_distance = double(M * N) / inverse_distances;
  double paired_squares = 0.0;  // collapsed strata: a pair's difference squared estimates its two strata's variance
  for (int j = 0; j < M; ++j)
    for (int k = 1; k < N; k += 2) paired_squares += std::pow(luminance(L[at(j, k)]) - luminance(L[at(j, k - 1)]), 2);
  double standard_error = kPi / (M * N) * std::sqrt(paired_squares);
  // 0 where every stratum was black; infinite where E is black but strata were not (as the kernel says).
  rec.relative_error = standard_error > 0.0 ? standard_error / luminance(rec.irradiance) : 0.0;
  rec.pixel_size = pixel_size;
  rec.pixel = pixel;
  double unclamped = rec.harmonic_distance;
  if (hp.hessian_error > 0.0f) {
    double curvature = relative_irradiance_curvature(dirs, L, r, M, N, n, t, b, 0.25 * pixel_size,
                                                     1e3 * hp.max_radius_pixels * pixel_size) *
                       pixel_size * pixel_size;
    unclamped = curvature > 0.0 ? pixel_size * std::pow(hp.hessian_error / curvature, 0.25)
                                : std::numeric_limits<double>::infinity();
  }
  rec.radius = std::clamp(unclamped, hp.min_radius_pixels * pixel_size, hp.max_radius_pixels * pixel_size);
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
  out.relative_error = float(r.relative_error);
  for (size_t s = 0; s < r.horizon.size(); ++s) out.horizon[s] = float(r.horizon[s]);
  return out;
}

}  // namespace rcsplat
