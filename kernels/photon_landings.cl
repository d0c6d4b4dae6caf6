// The photon map's photons gathered on the device (host/passes/photon_landings_pass.h): of each round's landings the
// lit ones, in their order, appended to the photons kept (the host's lit_landings, host/cache/photon_map.cpp), their
// flux scaled by the round's share, and every n-th of them taken for the lookup grid.
#include "shared_types.h"

// 1 where a landing hit a surface with some flux arriving.
__kernel void flag_lit_landings(__global const PhotonHit* landings, uint count, __global uint* lit) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  const PhotonHit p = landings[i];
  lit[i] = p.hit && (p.incident[0] > 0.0f || p.incident[1] > 0.0f || p.incident[2] > 0.0f) ? 1u : 0u;
}

// The lit landings to kept[first + place], place the scan of the flags: the landings' own order.
__kernel void append_lit_landings(__global const PhotonHit* landings, uint count, __global const uint* lit,
                                  __global const uint* places, uint first, __global PhotonHit* kept) {
  const size_t i = get_global_id(0);
  if (i < count && lit[i]) kept[first + places[i]] = landings[i];
}

// Every kept photon's reflected and arriving flux times share (R rounds each carry 1 / R of the lights' power).
__kernel void scale_photon_flux(__global PhotonHit* photons, uint count, float share) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  for (int c = 0; c < 3; ++c) {
    photons[i].flux[c] *= share;
    photons[i].incident[c] *= share;
  }
}

// taken[k] = photons[k * stride]: the lookup photons.
__kernel void take_every_nth(__global const PhotonHit* photons, uint taken_count, uint stride,
                             __global PhotonHit* taken) {
  const size_t k = get_global_id(0);
  if (k < taken_count) taken[k] = photons[k * stride];
}
