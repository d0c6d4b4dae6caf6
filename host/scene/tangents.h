// Tangents for normal maps where a glTF file gives none. The glTF specification asks for MikkTSpace's; this is the
// per-vertex average of the triangles' texture-coordinate gradients (Lengyel's method), which gives the same frame as
// MikkTSpace wherever a vertex's triangles agree on it (flat and smoothly curved patches away from UV seams; a seam's
// vertices are split in the file, so each side keeps its own). docs/NOTES.md "Normal maps" says what differs.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rcsplat {

// One tangent per vertex for the triangle list `indices` over `positions` (and `normals`, per vertex, or empty: then
// each triangle's own normal), texture coordinates `uvs` (2 floats a vertex, glTF's: v grows down the image). xyz: the
// unit direction of growing u, made orthogonal to the normal; w: +-1, the bitangent cross(normal, tangent) * w
// pointing up the image (glTF's green channel). A vertex no triangle with a texture-coordinate gradient touches gets
// w = 0: "no normal map here" (kernels/surface.h).
std::vector<glm::vec4> generate_tangents(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals, const std::vector<float>& uvs);

}  // namespace rcsplat
