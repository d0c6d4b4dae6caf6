#include "scene/tangents.h"

#include <algorithm>
#include <cmath>

namespace rcsplat {
namespace {

// The angle at corner p0 of the triangle p0, p1, p2.
double corner_angle(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2) {
  const glm::dvec3 a = p1 - p0, b = p2 - p0;
  const double la = glm::length(a), lb = glm::length(b);
  if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
}

}  // namespace

std::vector<glm::vec4> generate_tangents(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals, const std::vector<float>& uvs) {
  const size_t corners = indices.size() - indices.size() % 3;
  // Per corner: the triangle's handedness (+1, -1; 0 without a gradient) and its tangent direction projected onto
  // the corner's tangent plane, unit, weighted by the corner's angle (as MikkTSpace weighs them).
  std::vector<int> handedness(corners, 0);
  std::vector<glm::dvec3> weighted(corners, glm::dvec3(0.0)), corner_normal(corners, glm::dvec3(0.0));
  for (size_t t = 0; t < corners; t += 3) {
    const uint32_t i[3] = {indices[t], indices[t + 1], indices[t + 2]};
    const glm::dvec3 p[3] = {glm::dvec3(positions[i[0]]), glm::dvec3(positions[i[1]]), glm::dvec3(positions[i[2]])};
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0], face = glm::cross(e1, e2);
    const glm::dvec2 uv0(uvs[2 * i[0]], uvs[2 * i[0] + 1]);
    const glm::dvec2 d1 = glm::dvec2(uvs[2 * i[1]], uvs[2 * i[1] + 1]) - uv0;
    const glm::dvec2 d2 = glm::dvec2(uvs[2 * i[2]], uvs[2 * i[2] + 1]) - uv0;
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det) || !(glm::length(face) > 0.0)) continue;  // no gradient
    // e = dP/du du + dP/dv dv for both edges, solved for the gradients.
    const glm::dvec3 dp_du = (e1 * d2.y - e2 * d1.y) / det, dp_dv = (e2 * d1.x - e1 * d2.x) / det;
    const glm::dvec3 unit_face = glm::normalize(face);
    // The image's up is -dP/dv (glTF's v grows down the image; a normal map's green channel points up): +1 where
    // cross(n, dP/du) points that way.
    const int hand = glm::dot(glm::cross(unit_face, dp_du), -dp_dv) < 0.0 ? -1 : 1;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 n = normals.empty() ? unit_face : glm::dvec3(normals[i[k]]);
      if (!(glm::length(n) > 0.0)) n = unit_face;
      n = glm::normalize(n);
      const glm::dvec3 t_plane = dp_du - glm::dot(dp_du, n) * n;
      const double len = glm::length(t_plane);
      if (!(len > 0.0) || !std::isfinite(len)) continue;
      handedness[t + size_t(k)] = hand;
      corner_normal[t + size_t(k)] = n;
      weighted[t + size_t(k)] = corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]) * t_plane / len;
    }
  }
  // A corner's tangent: the sum over the corners of the same vertex with the same handedness (triangles mirrored in
  // texture space keep frames of their own, as MikkTSpace splits them), made orthogonal to its normal.
  std::vector<glm::dvec3> sum_positive(positions.size(), glm::dvec3(0.0)), sum_negative(positions.size(), glm::dvec3(0.0));
  for (size_t c = 0; c < corners; ++c) {
    if (handedness[c] > 0) sum_positive[indices[c]] += weighted[c];
    if (handedness[c] < 0) sum_negative[indices[c]] += weighted[c];
  }
  std::vector<glm::vec4> out(corners, glm::vec4(0.0f));
  for (size_t c = 0; c < corners; ++c) {
    if (handedness[c] == 0) continue;
    const glm::dvec3 n = corner_normal[c], sum = handedness[c] > 0 ? sum_positive[indices[c]] : sum_negative[indices[c]];
    const glm::dvec3 t = sum - glm::dot(sum, n) * n;
    const double len = glm::length(t);
    if (!(len > 0.0) || !std::isfinite(len)) continue;
    out[c] = glm::vec4(glm::vec3(t / len), float(handedness[c]));
  }
  return out;
}

}  // namespace rcsplat
