// Host twin of offset_ray_origin in kernels/sampling.h (the same ULP-scaled offset), for host-side ray casting.
#pragma once
#include <glm/glm.hpp>

#include <cmath>
#include <cstring>

namespace rcsplat {

inline glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n) {
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (std::fabs(p[i]) < 1.0f / 32.0f) {
      out[i] = p[i] + (1.0f / 65536.0f) * n[i];
      continue;
    }
    int32_t bits, ulps = int32_t(256.0f * n[i]);
    std::memcpy(&bits, &p[i], 4);
    bits += p[i] < 0.0f ? -ulps : ulps;
    std::memcpy(&out[i], &bits, 4);
  }
  return out;
}

}  // namespace rcsplat
