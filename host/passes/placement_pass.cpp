#include "passes/placement_pass.h"

#include "passes/ray_cast_pass.h"

namespace rcsplat {

PlacementPass::PlacementPass(GpuContext& gpu, const GBufferPass& gbuffer, int width, int height)
    : gpu_(gpu), gbuffer_(gbuffer), width_(width), height_(height) {
  cl::Program& program = gpu_.program("placement.cl");
  covered_kernel_ = cl::Kernel(program, "mark_covered");
  find_ = cl::Kernel(program, "find_uncovered");
  mark_ = cl::Kernel(program, "mark_records");
  clamp_ = cl::Kernel(program, "clamp_neighbours");
  apply_ = cl::Kernel(program, "apply_radii");
  size_t pixels = size_t(width) * size_t(height);
  candidates_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, pixels * sizeof(cl_uint));
  count_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE);
  record_map_ = gpu_.upload(std::vector<cl_int>(pixels, -1), CL_MEM_READ_WRITE);
  covered_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, pixels);
  tiles_ = size_t((width + 15) / 16) * size_t((height + 15) / 16);  // NEW_TILE in placement.cl
  new_in_tile_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, tiles_);
}

uint32_t PlacementPass::find_uncovered(const cl::Buffer& records, uint32_t record_count, float accuracy, int spacing,
                                       uint32_t unchanged_before) {
  size_t pixels = size_t(width_) * size_t(height_);
  if (!unchanged_before) gpu_.queue().enqueueFillBuffer(covered_, cl_uchar(0), 0, pixels);
  if (record_count > unchanged_before) {
    int a = 0;
    covered_kernel_.setArg(a++, records);
    covered_kernel_.setArg(a++, cl_uint(unchanged_before));
    covered_kernel_.setArg(a++, cl_uint(record_count - unchanged_before));
    covered_kernel_.setArg(a++, accuracy);
    covered_kernel_.setArg(a++, gbuffer_.samples());
    covered_kernel_.setArg(a++, gbuffer_.camera());
    covered_kernel_.setArg(a++, spacing);
    covered_kernel_.setArg(a++, covered_);
    gpu_.queue().enqueueNDRangeKernel(covered_kernel_, cl::NullRange,
                                      cl::NDRange(round_up(record_count - unchanged_before, 8)), cl::NDRange(8));
  }
  gpu_.queue().enqueueFillBuffer(count_, cl_uint(0), 0, sizeof(cl_uint));
  int a = 0;
  find_.setArg(a++, gbuffer_.samples());
  find_.setArg(a++, covered_);
  find_.setArg(a++, record_map_);
  find_.setArg(a++, width_);
  find_.setArg(a++, height_);
  find_.setArg(a++, spacing);
  find_.setArg(a++, candidates_);
  find_.setArg(a++, count_);
  size_t gx = (size_t(width_) + spacing - 1) / spacing, gy = (size_t(height_) + spacing - 1) / spacing;
  gpu_.queue().enqueueNDRangeKernel(find_, cl::NullRange, cl::NDRange(round_up(gx, 8), round_up(gy, 8)),
                                    cl::NDRange(8, 8));
  return gpu_.download<cl_uint>(count_, 1)[0];
}

void PlacementPass::mark(const cl::Buffer& records, uint32_t first, uint32_t count) {
  if (!count) return;
  gpu_.queue().enqueueFillBuffer(new_in_tile_, cl_uchar(0), 0, tiles_);
  mark_.setArg(0, records);
  mark_.setArg(1, cl_uint(first));
  mark_.setArg(2, cl_uint(count));
  mark_.setArg(3, record_map_);
  mark_.setArg(4, width_);
  mark_.setArg(5, new_in_tile_);
  gpu_.queue().enqueueNDRangeKernel(mark_, cl::NullRange, cl::NDRange(round_up(count, 64)), cl::NDRange(64));
}

void PlacementPass::clamp_neighbours(cl::Buffer& records, uint32_t count, uint32_t first_new, bool clamp_older,
                                     float min_spacing) {
  if (!count) return;
  if (count > radii_capacity_) {
    radii_capacity_ = std::max<size_t>(count, radii_capacity_ * 2);
    radii_ = cl::Buffer(gpu_.context(), CL_MEM_READ_WRITE, radii_capacity_ * sizeof(float));
  }
  int a = 0;
  clamp_.setArg(a++, records);
  clamp_.setArg(a++, cl_uint(count));
  clamp_.setArg(a++, cl_uint(first_new));
  clamp_.setArg(a++, cl_int(clamp_older ? 1 : 0));
  clamp_.setArg(a++, record_map_);
  clamp_.setArg(a++, new_in_tile_);
  clamp_.setArg(a++, gbuffer_.camera());
  clamp_.setArg(a++, min_spacing);
  clamp_.setArg(a++, radii_);
  gpu_.queue().enqueueNDRangeKernel(clamp_, cl::NullRange, cl::NDRange(round_up(count, 8)), cl::NDRange(8));
  apply_.setArg(0, records);
  apply_.setArg(1, cl_uint(count));
  apply_.setArg(2, radii_);
  gpu_.queue().enqueueNDRangeKernel(apply_, cl::NullRange, cl::NDRange(round_up(count, 64)), cl::NDRange(64));
  gpu_.queue().finish();
}

std::vector<int32_t> PlacementPass::record_at_pixel() {
  return gpu_.download<int32_t>(record_map_, size_t(width_) * size_t(height_));
}

}  // namespace rcsplat
