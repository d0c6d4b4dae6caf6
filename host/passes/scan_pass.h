// Exclusive prefix sums of uints on the device (kernels/scan.cl), for compactions that keep their order (placement's
// candidates). Owns the block sums of each level of the scan.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"

namespace rcsplat {

class ScanPass {
 public:
  explicit ScanPass(GpuContext& gpu);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);
  // out[i] = in[0] + ... + in[i - 1] for i < count (out[0] = 0); in and out are different buffers. Sums wrap at 2^32.
  void exclusive(const cl::Buffer& in, uint32_t count, const cl::Buffer& out);

 private:
  static constexpr const char* kProgram = "scan.cl";  // its kernels' file
  // One level: count elements in blocks of SCAN_BLOCK, then the blocks' sums scanned by the next level.
  void scan_level(const cl::Buffer& in, uint32_t count, const cl::Buffer& out, size_t level);

  struct Level {
    cl::Buffer sums, offsets;  // each block's total; their exclusive scan
    size_t sums_capacity = 0, offsets_capacity = 0;  // blocks the buffers hold
  };
  GpuContext& gpu_;
  NamedKernel blocks_, add_;
  std::vector<Level> levels_;
};

}  // namespace rcsplat
