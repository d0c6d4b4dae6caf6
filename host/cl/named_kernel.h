// Kernels whose arguments are set by name. Programs are built with -cl-kernel-arg-info, so each kernel reports its
// parameters' names and types (clGetKernelArgInfo); set() finds the parameter by name and refuses a value whose type
// does not match, and launch() refuses a kernel with a parameter left unset. A swapped pair of buffers is an error
// that names the kernel and the parameter, not a wrong image. On a driver that keeps no argument information the
// arguments are set in the order of the calls, which tests/kernel_args_test.cpp checks is the kernel's own order.
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

#include "kernels/shared_types.h"

namespace rcsplat {

class GpuContext;

// The name OpenCL gives a host type in a kernel signature: "uint", "float4", "CacheRecord".
template <typename T>
struct ClTypeName;
#define RCSPLAT_CL_TYPE_NAME(T, NAME) \
  template <>                         \
  struct ClTypeName<T> {              \
    static constexpr const char* value = NAME; \
  };
RCSPLAT_CL_TYPE_NAME(cl_uint, "uint")
RCSPLAT_CL_TYPE_NAME(cl_int, "int")
RCSPLAT_CL_TYPE_NAME(cl_ulong, "ulong")
RCSPLAT_CL_TYPE_NAME(cl_long, "long")
RCSPLAT_CL_TYPE_NAME(cl_uchar, "uchar")
RCSPLAT_CL_TYPE_NAME(cl_float, "float")
RCSPLAT_CL_TYPE_NAME(cl_double, "double")
RCSPLAT_CL_TYPE_NAME(cl_float2, "float2")
RCSPLAT_CL_TYPE_NAME(cl_float4, "float4")
RCSPLAT_CL_TYPE_NAME(cl_float8, "float8")
RCSPLAT_CL_TYPE_NAME(TriangleShading, "TriangleShading")
RCSPLAT_CL_TYPE_NAME(Material, "Material")
RCSPLAT_CL_TYPE_NAME(TextureInfo, "TextureInfo")
RCSPLAT_CL_TYPE_NAME(PunctualLight, "PunctualLight")
RCSPLAT_CL_TYPE_NAME(EmissiveTriangle, "EmissiveTriangle")
RCSPLAT_CL_TYPE_NAME(CameraParams, "CameraParams")
RCSPLAT_CL_TYPE_NAME(GBufferSample, "GBufferSample")
RCSPLAT_CL_TYPE_NAME(SurfaceLayers, "SurfaceLayers")
RCSPLAT_CL_TYPE_NAME(PixelSurface, "PixelSurface")
RCSPLAT_CL_TYPE_NAME(RayDesc, "RayDesc")
RCSPLAT_CL_TYPE_NAME(HitDesc, "HitDesc")
RCSPLAT_CL_TYPE_NAME(QueuedPath, "QueuedPath")
RCSPLAT_CL_TYPE_NAME(QueuedRay, "QueuedRay")
RCSPLAT_CL_TYPE_NAME(CacheRecord, "CacheRecord")
RCSPLAT_CL_TYPE_NAME(SceneCounts, "SceneCounts")
RCSPLAT_CL_TYPE_NAME(DirectParams, "DirectParams")
RCSPLAT_CL_TYPE_NAME(PathParams, "PathParams")
RCSPLAT_CL_TYPE_NAME(GlassMirrorParams, "GlassMirrorParams")
RCSPLAT_CL_TYPE_NAME(GlossyParams, "GlossyParams")
RCSPLAT_CL_TYPE_NAME(RecordBatchParams, "RecordBatchParams")
RCSPLAT_CL_TYPE_NAME(GuideCluster, "GuideCluster")
RCSPLAT_CL_TYPE_NAME(RecordGuideCones, "RecordGuideCones")
RCSPLAT_CL_TYPE_NAME(PhotonHit, "PhotonHit")
RCSPLAT_CL_TYPE_NAME(CausticMapLevel, "CausticMapLevel")
RCSPLAT_CL_TYPE_NAME(SurfacePatch, "SurfacePatch")
RCSPLAT_CL_TYPE_NAME(PhotonParams, "PhotonParams")
RCSPLAT_CL_TYPE_NAME(PhotonMapParams, "PhotonMapParams")
RCSPLAT_CL_TYPE_NAME(WorldRecordParams, "WorldRecordParams")
RCSPLAT_CL_TYPE_NAME(WorldRecordExtent, "WorldRecordExtent")
RCSPLAT_CL_TYPE_NAME(HshRecordParams, "HshRecordParams")
RCSPLAT_CL_TYPE_NAME(RadianceSplatParams, "RadianceSplatParams")
RCSPLAT_CL_TYPE_NAME(PlacementParams, "PlacementParams")
RCSPLAT_CL_TYPE_NAME(SplatParams, "SplatParams")
RCSPLAT_CL_TYPE_NAME(RayCastParams, "RayCastParams")
RCSPLAT_CL_TYPE_NAME(BrdfMaterial, "BrdfMaterial")
RCSPLAT_CL_TYPE_NAME(BrdfTableParams, "BrdfTableParams")
#undef RCSPLAT_CL_TYPE_NAME

inline size_t round_up(size_t n, size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

class NamedKernel {
 public:
  NamedKernel() = default;
  NamedKernel(GpuContext& gpu, cl::Program& program, const std::string& name);

  // A parameter passed by value (a scalar or a parameter struct).
  template <typename T>
  NamedKernel& set(const std::string& name, const T& value) {
    kernel_.setArg(index_of(name, ClTypeName<T>::value), value);
    return *this;
  }
  // A __global T* parameter.
  template <typename T>
  NamedKernel& set_buffer(const std::string& name, const cl::Buffer& buffer) {
    kernel_.setArg(index_of(name, std::string(ClTypeName<T>::value) + "*"), buffer);
    return *this;
  }

  // Enqueues `items` work-items (rounded up to whole groups) in groups of `group` fitted to the kernel on this device
  // (fitted_group), or a 2-D grid of tiles; every parameter must have been set since the last launch.
  void launch(size_t items, size_t group);
  void launch_2d(size_t width, size_t height, size_t tile_side);
  // `wanted` cut to what the kernel can run with on its device, and to a whole number of the device's preferred
  // multiple where it is at least one: the group launch() runs.
  size_t fitted_group(size_t wanted) const;
  const std::string& name() const { return name_; }
  // Whether the driver reported the parameters' names and types (else the order of the set() calls binds).
  bool bound_by_name() const { return by_name_; }

 private:
  struct Parameter {
    std::string name, type;
    bool set = false;
  };
  cl_uint index_of(const std::string& name, const std::string& type);
  void enqueue(const cl::NDRange& global, const cl::NDRange& local);
  void forget_arguments();  // each launch sets every parameter anew

  GpuContext* gpu_ = nullptr;
  cl::Kernel kernel_;
  std::string name_;
  std::vector<Parameter> parameters_;
  bool by_name_ = false;  // the driver reported the parameters' names
  size_t max_group_ = 1, group_multiple_ = 1;
  cl_uint next_in_order_ = 0;
  bool in_order_ = true;  // this launch's parameters were set in the kernel's order
};

}  // namespace rcsplat
