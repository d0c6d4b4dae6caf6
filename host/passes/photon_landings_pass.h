// The photon map's photons gathered on the device (kernels/photon_landings.cl): each round's lit landings appended in
// order to the photons kept (what the host's lit_landings keeps, bit for bit), their flux scaled by the rounds' share,
// and every n-th taken for the lookups. Owns the kept photons and the flags and places of a round's compaction.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "passes/scan_pass.h"

namespace rcsplat {

class PhotonLandingsPass {
 public:
  explicit PhotonLandingsPass(GpuContext& gpu);
  // Starts building its programs (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);

  // Appends the lit ones of `count` landings (PhotonHit) to the photons kept, in their order: 8 bytes read back, the
  // round's count.
  void append_lit(const cl::Buffer& landings, uint32_t count);
  // The photons kept are these (a cache file's), uploaded.
  void load(const std::vector<PhotonHit>& photons);
  // Every photon kept: its reflected and arriving flux times share.
  void scale_flux(float share);
  // photons[0], photons[stride], ...: into a new buffer of ceil(kept / stride) photons.
  cl::Buffer take_every(uint32_t stride, uint32_t& taken);

  const cl::Buffer& photons() const { return kept_; }  // kept() of them
  uint32_t kept() const { return kept_count_; }

 private:
  static constexpr const char* kProgram = "photon_landings.cl";  // its kernels' file
  GpuContext& gpu_;
  ScanPass scan_;
  NamedKernel flag_, append_, scale_, take_;
  cl::Buffer kept_, lit_, places_;
  uint32_t kept_count_ = 0;
  size_t kept_capacity_ = 0, lit_capacity_ = 0, places_capacity_ = 0;
};

}  // namespace rcsplat
