#include "scene/tangents.h"

#include <cmath>

namespace rcsplat {

std::vector<glm::vec4> generate_tangents(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals, const std::vector<float>& uvs) {
  const size_t vertices = positions.size();
  std::vector<glm::dvec3> along_u(vertices, glm::dvec3(0.0)), up_image(vertices, glm::dvec3(0.0)),
      face_normal(vertices, glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t i[3] = {indices[t], indices[t + 1], indices[t + 2]};
    const glm::dvec3 p0(positions[i[0]]), e1 = glm::dvec3(positions[i[1]]) - p0, e2 = glm::dvec3(positions[i[2]]) - p0;
    const glm::dvec2 uv0(uvs[2 * i[0]], uvs[2 * i[0] + 1]);
    const glm::dvec2 d1 = glm::dvec2(uvs[2 * i[1]], uvs[2 * i[1] + 1]) - uv0;
    const glm::dvec2 d2 = glm::dvec2(uvs[2 * i[2]], uvs[2 * i[2] + 1]) - uv0;
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) continue;  // no gradient: the triangle says nothing
    // e = dP/du du + dP/dv dv for both edges, solved for the gradients. Unnormalised, so larger triangles weigh more.
    const glm::dvec3 dp_du = (e1 * d2.y - e2 * d1.y) / det, dp_dv = (e2 * d1.x - e1 * d2.x) / det;
    const glm::dvec3 n = glm::cross(e1, e2);
    for (uint32_t k : i) {
      along_u[k] += dp_du;
      up_image[k] -= dp_dv;  // glTF's v grows down the image; the map's green channel points up it
      face_normal[k] += n;
    }
  }
  std::vector<glm::vec4> out(vertices, glm::vec4(0.0f));
  for (size_t v = 0; v < vertices; ++v) {
    glm::dvec3 n = normals.empty() ? face_normal[v] : glm::dvec3(normals[v]);
    const double n_length = glm::length(n);
    if (!(n_length > 0.0) || !std::isfinite(n_length)) continue;
    n /= n_length;
    const glm::dvec3 t = along_u[v] - glm::dot(along_u[v], n) * n;
    const double t_length = glm::length(t);
    if (!(t_length > 0.0) || !std::isfinite(t_length)) continue;
    const double w = glm::dot(glm::cross(n, t), up_image[v]) < 0.0 ? -1.0 : 1.0;
    out[v] = glm::vec4(glm::vec3(t / t_length), float(w));
  }
  return out;
}

}  // namespace rcsplat
