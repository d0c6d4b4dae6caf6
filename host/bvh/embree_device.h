// One Embree device per process, shared by the BVH builder and the reference ray caster (tests, benchmarks, references).
#pragma once
#include <embree3/rtcore.h>

namespace rcsplat {
RTCDevice embree_device();
}
