#include "cl/device_bvh.h"

namespace rcsplat {

DeviceBvh::DeviceBvh(GpuContext& gpu, const Bvh8& bvh)
    : nodes_(gpu.upload(bvh.nodes)), blocks_(gpu.upload(bvh.blocks)), stack_size_(bvh.stack_size()) {}

void DeviceBvh::add_defines(KernelDefines& defines) const {
  // Rounded up to a multiple of 16 so that scenes of similar depth share one compiled program.
  defines["BVH_STACK_SIZE"] = std::to_string((stack_size_ + 15) / 16 * 16);
}

}  // namespace rcsplat
