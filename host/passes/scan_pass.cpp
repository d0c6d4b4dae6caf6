#include "passes/scan_pass.h"

#include <algorithm>
#include <string>

#include "util/error.h"

namespace rcsplat {
void ScanPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }

ScanPass::ScanPass(GpuContext& gpu)
    : gpu_(gpu), blocks_(gpu.kernel(kProgram, "scan_blocks")), add_(gpu.kernel(kProgram, "add_block_offsets")) {}

void ScanPass::exclusive(const cl::Buffer& in, uint32_t count, const cl::Buffer& out) {
  if (count) scan_level(in, count, out, 0);
}

void ScanPass::scan_level(const cl::Buffer& in, uint32_t count, const cl::Buffer& out, size_t level) {
  const size_t blocks = (size_t(count) + SCAN_BLOCK - 1) / SCAN_BLOCK;
  if (levels_.size() <= level) levels_.resize(level + 1);
  Level& l = levels_[level];
  gpu_.reserve<cl_uint>(l.sums, l.sums_capacity, blocks, "scan");
  gpu_.reserve<cl_uint>(l.offsets, l.offsets_capacity, blocks, "scan");
  blocks_.set_buffer<cl_uint>("in", in)
      .set("count", cl_uint(count))
      .set_buffer<cl_uint>("out", out)
      .set_buffer<cl_uint>("block_sums", l.sums);
  // The kernel's local scan takes exactly SCAN_GROUP items a group.
  if (blocks_.fitted_group(SCAN_GROUP) != SCAN_GROUP)
    throw Error("scan.cl: the device runs at most " + std::to_string(blocks_.fitted_group(SCAN_GROUP)) +
                " work items a group; the scan needs " + std::to_string(SCAN_GROUP));
  blocks_.launch(blocks * SCAN_GROUP, SCAN_GROUP);
  if (blocks == 1) return;
  // Handles, not references into levels_: the next level may grow it.
  const cl::Buffer sums = l.sums, offsets = l.offsets;
  scan_level(sums, uint32_t(blocks), offsets, level + 1);
  add_.set_buffer<cl_uint>("block_offsets", offsets).set("count", cl_uint(count)).set_buffer<cl_uint>("out", out);
  add_.launch(count, 256);
}

}  // namespace rcsplat
