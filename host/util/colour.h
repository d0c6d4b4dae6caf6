// Colour on the host, one definition each: Rec. 709 luminance of a linear RGB value (the weight the host gives a
// colour when it compares lights, photons, environment texels or radiance samples; the kernels' is sampling.h
// luminance(), the same weights in float) and the sRGB transfer function both ways.
#pragma once
#include <glm/glm.hpp>

#include <cmath>

#include "kernels/host_device.h"

namespace rcsplat {

inline double luminance(double r, double g, double b) {
  return RC_LUMINANCE_R * r + RC_LUMINANCE_G * g + RC_LUMINANCE_B * b;
}
inline double luminance(const glm::dvec3& c) { return luminance(c.x, c.y, c.z); }
inline double luminance(const glm::vec3& c) { return luminance(c.x, c.y, c.z); }
inline double luminance(const float* c) { return luminance(c[0], c[1], c[2]); }
// In float, as the kernels compute it (where the host must weigh as they do).
inline float luminance_f(float r, float g, float b) {
  return RC_FLOAT(RC_LUMINANCE_R) * r + RC_FLOAT(RC_LUMINANCE_G) * g + RC_FLOAT(RC_LUMINANCE_B) * b;
}

// An sRGB-encoded value in [0, 1] to linear, and back (image/tone_map.h has the PNG writer's float encoder).
inline double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
inline double linear_to_srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

}  // namespace rcsplat
