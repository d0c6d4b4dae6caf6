// Everything about the scene that the shading kernels read, on the device: the BVH, per-triangle shading data,
// materials, textures, lights. Also the one place that decides the kernels' compile-time switches from the scene.
#pragma once
#include <vector>

#include "bvh/bvh8.h"
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "passes/device_bvh.h"
#include "scene/scene.h"

namespace rcsplat {

// Host-side arrays in the shared layout, ready to upload; also used by the host reference renderers.
struct PackedScene {
  std::vector<TriangleShading> triangles;
  std::vector<Material> materials;
  std::vector<TextureInfo> textures;
  std::vector<uint32_t> texels;  // RGBA8, sRGB-encoded
  std::vector<PunctualLight> lights;
  std::vector<EmissiveTriangle> emitters;  // with a power-proportional selection CDF
};

PackedScene pack_scene(const Scene& scene);

class DeviceScene {
 public:
  DeviceScene(GpuContext& gpu, const Scene& scene, const Bvh8& bvh);

  const DeviceBvh& bvh() const { return bvh_; }
  const cl::Buffer& triangles() const { return triangles_; }
  const cl::Buffer& materials() const { return materials_; }
  const cl::Buffer& textures() const { return textures_; }
  const cl::Buffer& texels() const { return texels_; }
  const cl::Buffer& lights() const { return lights_; }
  const cl::Buffer& emitters() const { return emitters_; }
  cl_uint light_count() const { return light_count_; }
  cl_uint emitter_count() const { return emitter_count_; }

  // Sets the SHADING_SCENE_ARGS of kernels/bounce.h from argument index first; returns the next free index.
  cl_uint bind_shading_args(cl::Kernel& kernel, cl_uint first) const;

  // HAS_TEXTURES, HAS_PUNCTUAL_LIGHTS, HAS_EMITTERS, BVH_STACK_SIZE: a scene compiles only the code it needs.
  const KernelDefines& defines() const { return defines_; }

 private:
  DeviceBvh bvh_;
  cl::Buffer triangles_, materials_, textures_, texels_, lights_, emitters_;
  cl_uint light_count_ = 0, emitter_count_ = 0;
  KernelDefines defines_;
};

}  // namespace rcsplat
