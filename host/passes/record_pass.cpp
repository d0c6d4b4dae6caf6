#include "passes/record_pass.h"

#include "passes/ray_cast_pass.h"
#include "util/error.h"

namespace rcsplat {

RecordPass::RecordPass(GpuContext& gpu, const DeviceScene& scene, unsigned theta_strata) : gpu_(gpu), scene_(scene) {
  if (theta_strata == 0 || theta_strata > kMaxThetaStrata)
    throw Error("hemisphere: M must be between 1 and " + std::to_string(kMaxThetaStrata));
  // The kernel keeps one column of M strata in private memory: sizing it to M keeps that memory small.
  KernelDefines defines = scene_.defines();
  defines["MAX_THETA_STRATA"] = std::to_string(theta_strata);
  kernel_ = cl::Kernel(gpu_.program("records.cl", defines), "compute_records");
  ray_total_ = gpu_.upload(std::vector<cl_ulong>{0}, CL_MEM_READ_WRITE);
  reserve(1024);
}

void RecordPass::reserve(size_t count) {
  if (count <= capacity_) return;
  size_t grown = std::max(count, capacity_ * 2);
  cl::Buffer bigger(gpu_.context(), CL_MEM_READ_WRITE, grown * sizeof(CacheRecord));
  if (capacity_) gpu_.queue().enqueueCopyBuffer(records_, bigger, 0, 0, capacity_ * sizeof(CacheRecord));
  records_ = bigger;
  capacity_ = grown;
}

void RecordPass::compute(const cl::Buffer& gbuffer, const cl::Buffer& camera, const cl::Buffer& candidates,
                         uint32_t count, uint32_t first, const HemisphereParams& params) {
  if (count == 0) return;
  reserve(size_t(first) + count);
  cl_uint a = scene_.bind_shading_args(kernel_, 0);
  kernel_.setArg(a++, gbuffer);
  kernel_.setArg(a++, camera);
  kernel_.setArg(a++, candidates);
  kernel_.setArg(a++, cl_uint(count));
  kernel_.setArg(a++, cl_uint(first));
  kernel_.setArg(a++, params);
  kernel_.setArg(a++, records_);
  kernel_.setArg(a++, ray_total_);
  // Small groups: a batch at a coarse level has few records, and each runs hundreds of rays.
  constexpr size_t local = 8;
  gpu_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(round_up(count, local)), cl::NDRange(local));
  gpu_.queue().finish();
}

uint64_t RecordPass::rays_cast() { return gpu_.download<cl_ulong>(ray_total_, 1)[0]; }

std::vector<CacheRecord> RecordPass::download(size_t count) { return gpu_.download<CacheRecord>(records_, count); }

}  // namespace rcsplat
