#include "cl/device_bvh.h"

#include <algorithm>

namespace rcsplat {

DeviceBvh::DeviceBvh(GpuContext& gpu, const Bvh8& bvh)
    : nodes_(gpu.upload(bvh.nodes, CL_MEM_READ_ONLY, "BVH")), blocks_(gpu.upload(bvh.blocks, CL_MEM_READ_ONLY, "BVH")), stack_size_(bvh.stack_size()) {}

void DeviceBvh::write_rows(GpuContext& gpu, const Bvh8& bvh, const MovingBvh::Changed& rows) {
  for (const MovingBvh::Rows& r : rows.nodes)
    if (r.count)
      gpu.queue().enqueueWriteBuffer(nodes_, CL_TRUE, r.first * sizeof(Bvh8Node), r.count * sizeof(Bvh8Node),
                                     bvh.nodes.data() + r.first);
  for (const MovingBvh::Rows& r : rows.blocks)
    if (r.count)
      gpu.queue().enqueueWriteBuffer(blocks_, CL_TRUE, r.first * sizeof(TriangleBlock8),
                                     r.count * sizeof(TriangleBlock8), bvh.blocks.data() + r.first);
}

// At least 32: trees of one to three levels (small scenes, and a small scene's moving parts under their top level)
// then share one program instead of compiling two; the stack's size changes no result.
std::string bvh_stack_switch(int stack_size) { return std::to_string(std::max((stack_size + 15) / 16 * 16, 32)); }

void DeviceBvh::add_defines(KernelDefines& defines) const {
  defines["BVH_STACK_SIZE"] = bvh_stack_switch(stack_size_);
}

}  // namespace rcsplat
