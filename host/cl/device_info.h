// What rcsplat needs to know about an OpenCL device, and whether it can run on it.
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

namespace rcsplat {

struct DeviceInfo {
  cl::Device device;
  size_t index = 0;  // position in the list of every device of every platform (what --device N means)
  std::string platform_name;
  std::string name;
  std::string type;  // "GPU", "CPU", "accelerator", ...
  std::string version;
  std::string opencl_c_version;
  std::string driver_version;
  cl_uint compute_units = 0;
  cl_ulong global_memory = 0;
  cl_ulong max_allocation = 0;
  bool int64_atomics = false;
  bool fp64 = false;  // double precision (cl_khr_fp64): the photon map's surface patches are cut on the device
  bool is_gpu = false;
  std::vector<std::string> problems;  // empty when rcsplat can use the device

  bool usable() const { return problems.empty(); }
};

// Every device of every platform; an empty list when no platform is installed.
std::vector<DeviceInfo> list_devices();

// Picks a usable device: by index, by case-insensitive name substring, or (empty selector) the first usable GPU, then
// the first usable device. Throws rcsplat::Error naming the reason when none fits.
DeviceInfo select_device(const std::string& selector);

}  // namespace rcsplat
