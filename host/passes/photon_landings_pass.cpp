#include "passes/photon_landings_pass.h"

#include <algorithm>

#include "util/error.h"

namespace rcsplat {
void PhotonLandingsPass::build_ahead(GpuContext& gpu) {
  gpu.build_ahead(kProgram);
  ScanPass::build_ahead(gpu);
}

PhotonLandingsPass::PhotonLandingsPass(GpuContext& gpu)
    : gpu_(gpu),
      scan_(gpu),
      flag_(gpu.kernel(kProgram, "flag_lit_landings")),
      append_(gpu.kernel(kProgram, "append_lit_landings")),
      scale_(gpu.kernel(kProgram, "scale_photon_flux")),
      take_(gpu.kernel(kProgram, "take_every_nth")) {}

void PhotonLandingsPass::append_lit(const cl::Buffer& landings, uint32_t count) {
  if (!count) return;
  gpu_.reserve<cl_uint>(lit_, lit_capacity_, count, "photon landings");
  gpu_.reserve<cl_uint>(places_, places_capacity_, count, "photon landings");
  const size_t group = gpu_.groups().per_item;
  flag_.set_buffer<PhotonHit>("landings", landings).set("count", cl_uint(count)).set_buffer<cl_uint>("lit", lit_);
  flag_.launch(count, group);
  scan_.exclusive(lit_, count, places_);
  // The round's count: the last place and the last flag.
  cl_uint last[2];
  gpu_.queue().enqueueReadBuffer(places_, CL_FALSE, (count - 1) * sizeof(cl_uint), sizeof(cl_uint), &last[0]);
  gpu_.queue().enqueueReadBuffer(lit_, CL_TRUE, (count - 1) * sizeof(cl_uint), sizeof(cl_uint), &last[1]);
  const size_t lit = size_t(last[0]) + last[1];
  if (lit == 0) return;
  if (size_t(kept_count_) + lit > UINT32_MAX) throw Error("photon map: more than 2^32 photons kept");
  const size_t needed = kept_count_ + lit;
  gpu_.reserve<PhotonHit>(kept_, kept_capacity_, needed, "photon map", true);  // what is kept, copied
  append_.set_buffer<PhotonHit>("landings", landings)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("lit", lit_)
      .set_buffer<cl_uint>("places", places_)
      .set("first", cl_uint(kept_count_))
      .set_buffer<PhotonHit>("kept", kept_);
  append_.launch(count, group);
  kept_count_ = uint32_t(needed);
}

void PhotonLandingsPass::load(const std::vector<PhotonHit>& photons) {
  if (photons.size() > UINT32_MAX) throw Error("photon map: more than 2^32 photons kept");
  kept_ = gpu_.upload(photons, CL_MEM_READ_WRITE, "photon map");
  kept_capacity_ = std::max<size_t>(photons.size(), 1);
  kept_count_ = uint32_t(photons.size());
}

void PhotonLandingsPass::scale_flux(float share) {
  scale_.set_buffer<PhotonHit>("photons", kept_).set("count", cl_uint(kept_count_)).set("share", share);
  scale_.launch(kept_count_, gpu_.groups().per_item);
}

cl::Buffer PhotonLandingsPass::take_every(uint32_t stride, uint32_t& taken) {
  stride = std::max(stride, 1u);
  taken = uint32_t((size_t(kept_count_) + stride - 1) / stride);
  cl::Buffer out = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(taken, 1) * sizeof(PhotonHit), "photon map");
  take_.set_buffer<PhotonHit>("photons", kept_)
      .set("taken_count", cl_uint(taken))
      .set("stride", cl_uint(stride))
      .set_buffer<PhotonHit>("taken", out);
  take_.launch(taken, gpu_.groups().per_item);
  return out;
}

}  // namespace rcsplat
