// The display transform of rcsplat's PNGs, shared with the perceptual error (flip.h), which judges what a viewer sees:
// exposure in stops, a filmic curve (Narkowicz's 2015 fit of ACES) and the sRGB transfer function.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

namespace rcsplat {

inline float tone_map(float x) {
  x = std::max(x, 0.0f);
  return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

inline float srgb_encode(float x) { return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f; }

// Linear radiance to sRGB-encoded display values in [0, 1], as the PNG writer stores them before quantising.
inline std::vector<float> display_image(const std::vector<float>& linear, float exposure_stops) {
  const float scale = std::exp2(exposure_stops);
  std::vector<float> out(linear.size());
  for (size_t i = 0; i < linear.size(); ++i) {
    const float v = std::isfinite(linear[i]) ? linear[i] : 0.0f;
    out[i] = srgb_encode(tone_map(v * scale));
  }
  return out;
}

}  // namespace rcsplat
