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
  // What a move needs to place and weigh the emitters again (DeviceScene::move): each emitter's triangle, its mean
  // luminance in double, and the power and area (times its sides) it was chosen by.
  std::vector<uint32_t> emitter_triangle;
  std::vector<double> emitter_emitted, emitter_power, emitter_area;
  PackedEnvironment environment;
  bool glass_caustics = false;  // Scene::glass_light.caustics
};

// Positions and lights in `frame`'s coordinates (render() passes the fitted one; the identity keeps world units).
// Texels::left_out leaves `textures` and `texels` empty: the scene's plan reads neither, and building every texture's
// mip chain once more for it would double the work of packing a textured scene.
enum class Texels { packed, left_out };
PackedScene pack_scene(const Scene& scene, const SceneFrame& frame = {}, Texels texels = Texels::packed);

// The pieces pack_scene is made of, for a scene whose parts moved (DeviceScene::move writes again only what moved):
// triangle t's shading row (its emitter left at -1; twice its area in device units to twice_area), whether its
// material emits, an emitter's corner and edges from its triangle's row, the emitters' selection probabilities and CDF
// from their power and area, and the punctual lights.
TriangleShading pack_triangle(const Scene& scene, const SceneFrame& frame, size_t t, float* twice_area = nullptr);
bool emits(const Scene& scene, size_t t);
void place_emitter(const TriangleShading& triangle, float twice_area, EmissiveTriangle& emitter);
void select_emitters(std::vector<EmissiveTriangle>& emitters, const std::vector<double>& power,
                     const std::vector<double>& area);
std::vector<PunctualLight> pack_lights(const Scene& scene, const SceneFrame& frame);

// A vertex colour in TriangleShading's 10-bit-per-channel form, and back.
uint32_t pack_vertex_color(const glm::vec3& color);
glm::vec3 unpack_vertex_color(uint32_t packed);

}  // namespace rcsplat
