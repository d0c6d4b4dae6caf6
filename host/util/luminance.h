// Rec. 709 luminance of a linear RGB value, in double: the weight the host gives a colour when it compares lights,
// photons, environment texels or radiance samples (the kernels' is sampling.h luminance()).
#pragma once
#include <glm/glm.hpp>

namespace rcsplat {

inline double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
inline double luminance(const glm::dvec3& c) { return luminance(c.x, c.y, c.z); }
inline double luminance(const glm::vec3& c) { return luminance(c.x, c.y, c.z); }
inline double luminance(const float* c) { return luminance(c[0], c[1], c[2]); }

}  // namespace rcsplat
