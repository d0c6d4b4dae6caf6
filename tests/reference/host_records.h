// One irradiance record computed on the host in double precision with Embree rays: the same strata, random numbers and
// formulas as kernels/records.cl, written independently on purpose (all strata stored, walls summed over the grid,
// no code shared with the kernel): the record kernel's test reference (tests/records_test.cpp). Both cache methods
// render with the kernel's records.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "reference/host_shading.h"
#include "kernels/shared_types.h"

namespace rcsplat {

struct HostRecord {
  glm::dvec3 position{0.0}, normal{0.0}, irradiance{0.0};
  std::array<glm::dvec3, 3> grad_translation{}, grad_rotation{};  // row per axis, RGB
  double radius = 0, harmonic_distance = 0, pixel_size = 0;
  double relative_error = 0;  // E's standard error over E (luminance), from columns paired 2k, 2k + 1 row by row
  std::array<double, RECORD_HORIZON_SECTORS> horizon{};  // per 45-degree sector from t toward b
  uint32_t pixel = 0;
  uint64_t rays = 0;
  // What a radiance record projects onto HSH: each stratum's share of the light (after the light guide's balance-
  // heuristic weight), [row * N + column].
  std::vector<glm::dvec3> strata_radiance;
};

// p: surface point, n: shading normal, ng: geometric normal (both facing the viewer); pixel keys the random numbers.
// With a light guide (clusters, and params.guide_rays), also the guided rays and the balance-heuristic weights of
// kernels/light_guide.h, written again here in double precision.
HostRecord compute_host_record(const HostShading& shading, const glm::vec3& p, const glm::vec3& n, const glm::vec3& ng,
                               uint32_t pixel, double pixel_size, const HemisphereParams& params,
                               const std::vector<GuideCluster>& guide = {});

// The record in the device layout.
CacheRecord to_cache_record(const HostRecord& r);

// The light guide's cones as a point p (normal n) sees them, in double (kernels/light_guide.h guide_cones for a
// hemisphere of `strata` strata): the clusters' bounding spheres, each with its selection probability and inclusive
// cdf; their density of a unit direction; and the direction the guide draws from (u, v, w) (sample_guide).
struct HostGuideCone {
  glm::dvec3 axis{0.0};
  double cos_max = 1.0, solid_angle = 0.0, probability = 0.0, cdf = 0.0;
};
std::vector<HostGuideCone> host_guide_cones(const std::vector<GuideCluster>& guide, const glm::dvec3& p,
                                            const glm::dvec3& n, int strata);
double host_guide_density(const std::vector<HostGuideCone>& cones, const glm::dvec3& dir);
glm::dvec3 host_guide_direction(const std::vector<HostGuideCone>& cones, double u, double v, double w);

}  // namespace rcsplat
