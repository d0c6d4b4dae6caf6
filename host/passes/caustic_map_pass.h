// The caustic map (kernels/caustic_map.cl, docs/ALGORITHM.md section 8): photons from the lights that reflected off a
// sharp lobe (LOBE_GLOSSY) once before landing, sorted into a hashed grid on the host and read at every G-buffer
// sample as irradiance that composition reflects with the records' light. Made for scenes with such a lobe, where the
// irradiance records then leave that path out of their rays (kernels/bounce.h hit_direct_without_caustics).
#pragma once
#include <vector>

#include "cache/photon_map.h"
#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"

namespace rcsplat {

// The landings after one reflection off a LOBE_GLOSSY surface of `paths` photons from the scene's lights (the light
// guide's sources: punctual lights, emitters, the environment's peak), their flux each photon's share of the power.
std::vector<PhotonHit> shoot_caustic_photons(GpuContext& gpu, const DeviceScene& scene, unsigned paths, unsigned seed);

// The radius at which a photon of these has about `neighbours` others within it on average (full 3D distance), found
// from start (photon_gather_radius over the whole surface) by a few fixed-point steps on a fixed subsample, and never
// larger than start: caustic photons crowd into a small part of the surface, where the whole surface's radius would
// blur them. Deterministic: the same photons give the same radius.
float crowded_gather_radius(const std::vector<PhotonHit>& photons, float start, unsigned neighbours);
// How many of the grid's photons lie within its radius of photon p (p itself not counted), facing p's way; the count
// stops early, somewhere above `enough`, once it passes it.
size_t photon_neighbour_count(const PhotonGrid& grid, const PhotonHit& p, size_t enough = SIZE_MAX);

class CausticMapPass {
 public:
  // Sorts the photons into a grid of `radius` and uploads it.
  CausticMapPass(GpuContext& gpu, const std::vector<PhotonHit>& photons, float radius);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // irradiance[i] += the caustic irradiance at G-buffer sample i (float4 per sample, as the splat resolves it).
  void add_to(const GBufferView& gbuffer, const cl::Buffer& irradiance);
  // Records 0 .. record_count - 1 of `records` with the caustic irradiance at each one's point added to its own: the
  // records a glossy sample reads then stand for all the light there (kernels/glossy.cl), which costs one lookup per
  // record, not one per sample. A buffer this pass owns until the next call, or `records` itself for an empty map.
  const cl::Buffer& lit_records(const cl::Buffer& records, uint32_t record_count);
  // Sets a kernel's CAUSTIC_MAP_ARGS (kernels/caustic_map.h).
  void bind(NamedKernel& kernel) const;
  const PhotonMapParams& params() const { return params_; }

 private:
  static constexpr const char* kProgram = "caustic_map.cl";  // its kernels' file
  GpuContext& gpu_;
  PhotonMapParams params_;
  cl::Buffer photons_, buckets_;
  NamedKernel add_, add_to_records_;
  cl::Buffer lit_records_;
  size_t lit_capacity_ = 0;  // records lit_records_ holds
};

}  // namespace rcsplat
