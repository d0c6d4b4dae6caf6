#include "cl/device_info.h"

#include <algorithm>
#include <cctype>

#include "util/error.h"

namespace rcsplat {
namespace {

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  return s;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

DeviceInfo describe(const cl::Platform& platform, const cl::Device& device, size_t index) {
  DeviceInfo info;
  info.device = device;
  info.index = index;
  info.platform_name = trim(platform.getInfo<CL_PLATFORM_NAME>());
  info.name = trim(device.getInfo<CL_DEVICE_NAME>());
  cl_device_type type = device.getInfo<CL_DEVICE_TYPE>();
  info.type = type_name(type);
  info.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
  info.version = trim(device.getInfo<CL_DEVICE_VERSION>());
  info.opencl_c_version = trim(device.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
  info.driver_version = trim(device.getInfo<CL_DRIVER_VERSION>());
  info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  info.global_memory = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  info.max_allocation = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  std::string extensions = device.getInfo<CL_DEVICE_EXTENSIONS>();
  info.int64_atomics = extensions.find("cl_khr_int64_base_atomics") != std::string::npos;
  info.fp64 = extensions.find("cl_khr_fp64") != std::string::npos;
  if (!info.int64_atomics) info.problems.push_back("no 64-bit integer atomics (cl_khr_int64_base_atomics)");
  if (!device.getInfo<CL_DEVICE_COMPILER_AVAILABLE>()) info.problems.push_back("no OpenCL C compiler");
  if (!device.getInfo<CL_DEVICE_AVAILABLE>()) info.problems.push_back("device not available");
  if (info.global_memory < (256ull << 20)) info.problems.push_back("less than 256 MiB of global memory");
  return info;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> result;
  std::vector<cl::Platform> platforms;
  // clGetPlatformIDs fails with CL_PLATFORM_NOT_FOUND_KHR when no ICD is installed: that is an empty list, not an error.
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    return result;
  }
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices reports CL_DEVICE_NOT_FOUND
    }
    for (const cl::Device& device : devices) result.push_back(describe(platform, device, result.size()));
  }
  return result;
}

DeviceInfo select_device(const std::string& selector) {
  std::vector<DeviceInfo> devices = list_devices();
  if (devices.empty()) {
    throw Error(
        "no OpenCL device found: install an OpenCL driver (e.g. pocl-opencl-icd) and make sure POCL_CACHE_DIR, if set, "
        "is writable");
  }
  auto check = [](const DeviceInfo& d) {
    if (!d.usable()) {
      std::string why;
      for (const std::string& p : d.problems) why += (why.empty() ? "" : "; ") + p;
      throw Error("OpenCL device " + std::to_string(d.index) + " (" + d.name + ") cannot run rcsplat: " + why);
    }
    return d;
  };
  if (!selector.empty()) {
    bool numeric = std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
    if (numeric) {
      size_t index = std::stoul(selector);
      if (index >= devices.size()) {
        throw Error("--device " + selector + ": there are only " + std::to_string(devices.size()) +
                    " OpenCL devices (see `rcsplat devices`)");
      }
      return check(devices[index]);
    }
    for (const DeviceInfo& d : devices) {
      if (lower(d.name).find(lower(selector)) != std::string::npos) return check(d);
    }
    throw Error("--device " + selector + ": no OpenCL device name contains it (see `rcsplat devices`)");
  }
  for (const DeviceInfo& d : devices)
    if (d.is_gpu && d.usable()) return d;
  for (const DeviceInfo& d : devices)
    if (d.usable()) return d;
  return check(devices.front());
}

}  // namespace rcsplat
