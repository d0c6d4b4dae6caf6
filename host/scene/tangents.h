// Tangents for normal maps where a glTF file gives none, after MikkTSpace, which the glTF specification names: each
// triangle's texture-coordinate gradient along u, projected onto each corner's tangent plane, weighted by the corner's
// angle and summed over the corners that share a vertex and a handedness (triangles mirrored in texture space keep
// their own frames), then made orthogonal to the normal. What MikkTSpace does beyond this (splitting a vertex's
// corners whose tangents differ by more than a threshold angle, its degenerate-triangle repairs) is not done;
// docs/NOTES.md "Normal maps" says when that shows.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rcsplat {

// One tangent per corner of the triangle list `indices` (three a triangle, in its order) over `positions` (and
// `normals`, per vertex, or empty: then each triangle's own normal), texture coordinates `uvs` (2 floats a vertex,
// glTF's: v grows down the image). xyz: the unit direction of growing u, orthogonal to the corner's normal; w: +-1, the
// bitangent cross(normal, tangent) * w pointing up the image (glTF's green channel). A triangle without a
// texture-coordinate gradient gets w = 0: "no normal map here" (kernels/surface.h).
std::vector<glm::vec4> generate_tangents(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals, const std::vector<float>& uvs);

}  // namespace rcsplat
