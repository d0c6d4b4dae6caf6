// Everything about the scene that the ray-tracing kernels read, on the device: the BVH, per-triangle shading data,
// materials, textures, lights (kernels/scene_args.h SCENE_ARGS). Also the one place that decides the kernels'
// compile-time switches from the scene.
#pragma once
#include "bvh/bvh8.h"
#include "cl/device_bvh.h"
#include "cl/gpu_context.h"
#include "scene/packed_scene.h"

namespace rcsplat {

class DeviceScene {
 public:
  DeviceScene(GpuContext& gpu, const Scene& scene, const Bvh8& bvh);

  // Sets a kernel's SCENE_ARGS.
  void bind(NamedKernel& kernel) const;

  // HAS_TEXTURES, HAS_PUNCTUAL_LIGHTS, HAS_EMITTERS, BVH_STACK_SIZE: a scene compiles only the code it needs.
  const KernelDefines& defines() const { return defines_; }

 private:
  DeviceBvh bvh_;
  cl::Buffer triangles_, materials_, textures_, texels_, lights_, emitters_;
  SceneCounts counts_{};
  KernelDefines defines_;
};

}  // namespace rcsplat
