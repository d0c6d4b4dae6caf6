// The scene in the layout the kernels read (kernels/shared_types.h), as host arrays: what DeviceScene uploads and what
// the host's reference shading reads. No OpenCL here.
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/shared_types.h"
#include "scene/scene.h"
#include "scene/scene_frame.h"

namespace rcsplat {

// Host-side arrays in the shared layout, ready to upload; also used by the host reference renderers.
struct PackedScene {
  std::vector<TriangleShading> triangles;
  std::vector<float> tangents;  // with normal maps, 4 floats (Scene::tangents) per triangle vertex; else empty
  std::vector<Material> materials;
  std::vector<TextureInfo> textures;
  std::vector<uint32_t> texels;  // RGBA8, sRGB-encoded
  std::vector<PunctualLight> lights;
  std::vector<EmissiveTriangle> emitters;  // with a power-proportional selection CDF
  std::vector<float> emitter_mean_luminance;  // each emitter's luminance averaged over it (with its texture)
  PackedEnvironment environment;
  bool glass_caustics = false;  // Scene::glass_light.caustics
};

// Positions and lights in `frame`'s coordinates (render() passes the fitted one; the identity keeps world units).
// Texels::left_out leaves `textures` and `texels` empty: the scene's plan reads neither, and building every texture's
// mip chain once more for it would double the work of packing a textured scene.
enum class Texels { packed, left_out };
PackedScene pack_scene(const Scene& scene, const SceneFrame& frame = {}, Texels texels = Texels::packed);

// A vertex colour in TriangleShading's 10-bit-per-channel form, and back.
uint32_t pack_vertex_color(const glm::vec3& color);
glm::vec3 unpack_vertex_color(uint32_t packed);

}  // namespace rcsplat
