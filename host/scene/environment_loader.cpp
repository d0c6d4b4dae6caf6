// Reading an environment from the command line's settings (scene/environment.h); kept apart from the packing, which
// needs no image I/O (the scene fuzzer links the packing alone).
#include <algorithm>
#include <cmath>

#include "image/exr_file.h"
#include "scene/environment.h"
#include "util/error.h"

namespace rcsplat {
namespace {

bool finite_non_negative(const glm::vec3& c) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c[k]) || c[k] < 0.0f) return false;
  return true;
}

// The map's R, G and B channels (a single channel is grey): channel names first, else the first three.
std::vector<glm::vec3> read_map(const std::string& path, int& width, int& height) {
  ExrPixels image = read_exr_file(path);  // any format OpenImageIO reads (rcsplat's own EXR reader without it)
  const size_t channels = image.channels.size();
  if (image.width <= 0 || image.height <= 0 || channels == 0) throw Error(path + ": the environment map is empty");
  if (image.width > 32768 || image.height > 16384)
    throw Error(path + ": the environment map is " + std::to_string(image.width) + " x " +
                std::to_string(image.height) + "; at most 32768 x 16384 is supported");
  if (channels == 2) throw Error(path + ": the environment map has two channels; give RGB or grey");
  size_t pick[3] = {0, channels > 1 ? 1u : 0u, channels > 2 ? 2u : 0u};
  for (int k = 0; k < 3 && channels >= 3; ++k) {
    auto it = std::find(image.channels.begin(), image.channels.end(), std::string(1, "RGB"[k]));
    if (it != image.channels.end()) pick[k] = size_t(it - image.channels.begin());
  }
  width = image.width;
  height = image.height;
  std::vector<glm::vec3> rgb(size_t(width) * size_t(height));
  for (size_t i = 0; i < rgb.size(); ++i) {
    for (int k = 0; k < 3; ++k) rgb[i][k] = image.values[i * channels + pick[k]];
    if (!finite_non_negative(rgb[i]))
      throw Error(path + ": texel (" + std::to_string(i % size_t(width)) + ", " + std::to_string(i / size_t(width)) +
                  ") is " + format_rgb(rgb[i]) + "; an environment map's radiance must be finite and non-negative");
  }
  return rgb;
}

}  // namespace

Environment make_environment(const EnvironmentSettings& s) {
  Environment e;
  if (!s.requested()) return e;
  if (s.sky && !s.file.empty()) throw Error("--sky and --environment: give one or the other");
  if (!std::isfinite(s.intensity) || s.intensity < 0.0f)
    throw Error("--environment-intensity must be finite and non-negative");
  if (!std::isfinite(s.rotation_degrees)) throw Error("--environment-rotation must be finite");
  e.rotation_degrees = s.rotation_degrees;
  if (s.sky) {
    if (!finite_non_negative(*s.sky)) throw Error("--sky " + format_rgb(*s.sky) + ": must be finite and non-negative");
    e.width = e.height = 1;
    e.radiance = {*s.sky};
    return e;
  }
  e.source = s.file;
  e.intensity = s.intensity;
  e.radiance = read_map(s.file, e.width, e.height);
  for (glm::vec3& c : e.radiance) {
    c *= s.intensity;
    if (!finite_non_negative(c))
      throw Error(s.file + ": --environment-intensity " + std::to_string(s.intensity) + " overflows its texels");
  }
  return e;
}

}  // namespace rcsplat
