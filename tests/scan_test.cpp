// The device's exclusive scan (kernels/scan.cl, passes/scan_pass.h) against a host scan of the same random uints, at
// sizes across one block, several, and three levels of block sums: whole numbers, so equal.
#include "passes/scan_pass.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "test_support.h"

namespace rcsplat {
namespace {

TEST(Scan, ExclusivePrefixSumsEqualTheHosts) {
  GpuContext& gpu = test::gpu();
  ScanPass scan(gpu);
  std::mt19937 rng(7);
  // Values up to 2^12: a 1.1M-element scan reaches 2^32 and wraps, as the host's uint32 sum does.
  std::uniform_int_distribution<uint32_t> value(0, 1u << 12), flag(0, 1);
  for (uint32_t count : {1u, 5u, 1023u, 1024u, 1025u, 4096u + 3u, 300000u, 1100000u}) {
    std::vector<cl_uint> in(count);
    for (size_t i = 0; i < count; ++i) in[i] = count == 300000u ? flag(rng) : value(rng);
    const cl::Buffer device_in = gpu.upload(in, CL_MEM_READ_ONLY, "test");
    const cl::Buffer device_out = gpu.buffer(CL_MEM_READ_WRITE, count * sizeof(cl_uint), "test");
    scan.exclusive(device_in, count, device_out);
    const std::vector<cl_uint> out = gpu.download<cl_uint>(device_out, count);
    uint32_t running = 0;
    size_t wrong = 0, first_wrong = count;
    for (size_t i = 0; i < count; ++i) {
      if (out[i] != running && wrong++ == 0) first_wrong = i;
      running += in[i];
    }
    EXPECT_EQ(wrong, 0u) << count << " elements: first wrong at " << first_wrong;
  }
}

}  // namespace
}  // namespace rcsplat
