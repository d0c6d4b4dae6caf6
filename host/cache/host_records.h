// One irradiance record computed on the host in double precision with Embree rays: the same strata, random numbers and
// formulas as kernels/records.cl, written independently on purpose (all strata stored, walls summed over the grid,
// no code shared with the kernel): the record kernel's test reference (tests/records_test.cpp). Both cache methods
// render with the kernel's records.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "cache/host_shading.h"
#include "kernels/shared_types.h"

namespace rcsplat {

struct HostRecord {
  glm::dvec3 position{0.0}, normal{0.0}, irradiance{0.0};
  std::array<glm::dvec3, 3> grad_translation{}, grad_rotation{};  // row per axis, RGB
  double radius = 0, harmonic_distance = 0, pixel_size = 0;
  std::array<double, RECORD_HORIZON_SECTORS> horizon{};  // per 45-degree sector from t toward b
  uint32_t pixel = 0;
  uint64_t rays = 0;
  // What a radiance record projects onto HSH: each stratum's share of the light (after the light guide's balance-
  // heuristic weight), [row * N + column], and each guided ray that stayed above the surface: its direction in the
  // record's frame (t, b, n), its radiance and its weight 1 / (n_c p_c + n_g p_g).
  struct GuidedSample {
    glm::dvec3 direction{0.0}, radiance{0.0};
    double weight = 0;
  };
  std::vector<glm::dvec3> strata_radiance;
  std::vector<GuidedSample> guided;
};

// p: surface point, n: shading normal, ng: geometric normal (both facing the viewer); pixel keys the random numbers.
// With a light guide (clusters, and params.guide_rays), also the guided rays and the balance-heuristic weights of
// kernels/light_guide.h, written again here in double precision.
HostRecord compute_host_record(const HostShading& shading, const glm::vec3& p, const glm::vec3& n, const glm::vec3& ng,
                               uint32_t pixel, double pixel_size, const HemisphereParams& params,
                               const std::vector<GuideCluster>& guide = {});

// The record in the device layout.
CacheRecord to_cache_record(const HostRecord& r);

}  // namespace rcsplat
