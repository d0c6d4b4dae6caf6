#include "cl/device_bvh.h"

namespace rcsplat {

DeviceBvh::DeviceBvh(GpuContext& gpu, const Bvh8& bvh)
    : nodes_(gpu.upload(bvh.nodes, CL_MEM_READ_ONLY, "BVH")), blocks_(gpu.upload(bvh.blocks, CL_MEM_READ_ONLY, "BVH")), stack_size_(bvh.stack_size()) {}

std::string bvh_stack_switch(int stack_size) { return std::to_string((stack_size + 15) / 16 * 16); }

void DeviceBvh::add_defines(KernelDefines& defines) const {
  defines["BVH_STACK_SIZE"] = bvh_stack_switch(stack_size_);
}

}  // namespace rcsplat
