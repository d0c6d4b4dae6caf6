#include "cl/named_kernel.h"

#include <algorithm>

#include "cl/gpu_context.h"
#include "util/error.h"

namespace rcsplat {
namespace {

// "const CacheRecord *" and "struct SplatParams" as "CacheRecord*" and "SplatParams": drivers differ in spacing,
// qualifiers and the struct keyword, none of which the host binds by.
std::string plain_type(std::string type) {
  for (const char* word : {"struct ", "const ", "volatile ", "restrict "})
    for (size_t at; (at = type.find(word)) != std::string::npos;) type.erase(at, std::string(word).size());
  std::string out;
  for (char c : type)
    if (c != ' ') out += c;
  return out;
}

}  // namespace

NamedKernel::NamedKernel(GpuContext& gpu, cl::Program& program, const std::string& name)
    : gpu_(&gpu), kernel_(program, name.c_str()), name_(name) {
  cl_uint count = kernel_.getInfo<CL_KERNEL_NUM_ARGS>();
  parameters_.resize(count);
  by_name_ = true;
  for (cl_uint i = 0; i < count && by_name_; ++i) {
    cl_int status = CL_SUCCESS;
    parameters_[i].name = kernel_.getArgInfo<CL_KERNEL_ARG_NAME>(i, &status);
    if (status == CL_SUCCESS) parameters_[i].type = plain_type(kernel_.getArgInfo<CL_KERNEL_ARG_TYPE_NAME>(i, &status));
    by_name_ = status == CL_SUCCESS;
  }
  // The largest group this kernel can run with on this device (registers and local memory limit it on a GPU), and
  // the multiple the device runs groups in (a warp, a wavefront, PoCL's vector width).
  const cl::Device& device = gpu.device_info().device;
  max_group_ = std::max<size_t>(kernel_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device), 1);
  group_multiple_ = std::max<size_t>(kernel_.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device), 1);
  // The strings OpenCL returns may carry their terminating zero.
  for (Parameter& p : parameters_)
    for (std::string* s : {&p.name, &p.type})
      while (!s->empty() && s->back() == '\0') s->pop_back();
}

cl_uint NamedKernel::index_of(const std::string& name, const std::string& type) {
  cl_uint index = next_in_order_;
  if (by_name_) {
    index = 0;
    while (index < parameters_.size() && parameters_[index].name != name) ++index;
    if (index == parameters_.size()) throw Error("kernel " + name_ + " has no parameter '" + name + "'");
    if (parameters_[index].type != type)
      throw Error("kernel " + name_ + ": parameter '" + name + "' is " + parameters_[index].type + ", the host binds " +
                  type);
  } else if (index >= parameters_.size()) {
    throw Error("kernel " + name_ + " takes " + std::to_string(parameters_.size()) + " parameters; the host binds more");
  }
  in_order_ = in_order_ && index == next_in_order_;
  next_in_order_ = index + 1;
  parameters_[index].set = true;
  return index;
}

void NamedKernel::enqueue(const cl::NDRange& global, const cl::NDRange& local) {
  for (const Parameter& p : parameters_)
    if (!p.set) throw Error("kernel " + name_ + ": parameter '" + p.name + "' was not set before the launch");
  gpu_->note_launch(name_, in_order_ && next_in_order_ == parameters_.size());
  gpu_->queue().enqueueNDRangeKernel(kernel_, cl::NullRange, global, local);
  forget_arguments();
}

void NamedKernel::forget_arguments() {
  for (Parameter& p : parameters_) p.set = false;
  next_in_order_ = 0;
  in_order_ = true;
}

size_t NamedKernel::fitted_group(size_t wanted) const {
  size_t group = std::min(std::max<size_t>(wanted, 1), max_group_);
  if (group >= group_multiple_) group -= group % group_multiple_;
  return group;
}

void NamedKernel::launch(size_t items, size_t group) {
  if (items == 0) return forget_arguments();
  group = fitted_group(group);
  enqueue(cl::NDRange(round_up(items, group)), cl::NDRange(group));
}

void NamedKernel::launch_2d(size_t width, size_t height, size_t tile_side) {
  if (width == 0 || height == 0) return forget_arguments();
  enqueue(cl::NDRange(round_up(width, tile_side), round_up(height, tile_side)), cl::NDRange(tile_side, tile_side));
}

}  // namespace rcsplat
