// The BVH's node and triangle-block buffers on the device.
#pragma once
#include <string>

#include "bvh/bvh8.h"
#include "bvh/moving_bvh.h"
#include "cl/gpu_context.h"

namespace rcsplat {

// BVH_STACK_SIZE for a tree whose traversal needs stack_size entries (Bvh8::stack_size), rounded up to a multiple of 16
// and at least 32, so that scenes of similar depth share one compiled program.
std::string bvh_stack_switch(int stack_size);

class DeviceBvh {
 public:
  DeviceBvh(GpuContext& gpu, const Bvh8& bvh);

  // Writes the rows a move rewrote (bvh/moving_bvh.h); the tree keeps its size and depth.
  void write_rows(GpuContext& gpu, const Bvh8& bvh, const MovingBvh::Changed& rows);

  const cl::Buffer& nodes() const { return nodes_; }
  const cl::Buffer& blocks() const { return blocks_; }
  // The traversal stack's size, sized from the tree's depth so that it cannot overflow.
  void add_defines(KernelDefines& defines) const;

 private:
  cl::Buffer nodes_, blocks_;
  int stack_size_;
};

}  // namespace rcsplat
