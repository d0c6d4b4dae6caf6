// The scene in the layout the kernels read (kernels/shared_types.h), as host arrays: what DeviceScene uploads and what
// the host's reference shading reads. No OpenCL here.
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/shared_types.h"
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

}  // namespace rcsplat
