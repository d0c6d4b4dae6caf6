// One Embree device per process, shared by the BVH builder and the reference ray caster (tests, benchmarks, references).
// Embree reports errors through a callback and a per-device error code, not exceptions: check_embree turns them into
// rcsplat::Error after each call that can fail, so a failed build or commit stops the run with Embree's message.
#pragma once
#include <embree3/rtcore.h>

#include <string>

namespace rcsplat {

RTCDevice embree_device();

// Throws rcsplat::Error("Embree: <what> failed: ...") if Embree reported an error since the last check.
void check_embree(const std::string& what);

}  // namespace rcsplat
