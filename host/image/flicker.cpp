#include "image/flicker.h"

#include <cmath>
#include <numbers>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "image/error_metrics.h"
#include "image/exr_file.h"
#include "util/error.h"

namespace rcsplat {
namespace {

glm::dvec3 parse_vector(const std::string& text, bool* ok) {
  glm::dvec3 v(0.0);
  const char* p = text.c_str();
  for (int k = 0; k < 3; ++k) {
    char* end = nullptr;
    v[k] = std::strtod(p, &end);
    if (end == p || !std::isfinite(v[k]) || (k < 2 && *end != ',') || (k == 2 && *end != '\0')) *ok = false;
    p = *end ? end + 1 : end;
  }
  return v;
}

}  // namespace

ViewCamera parse_view_camera(const std::string& attribute, const std::string& source) {
  std::istringstream in(attribute);
  std::string kind, key, value;
  in >> kind;
  glm::dvec3 eye(0.0), target(0.0), up(0.0);
  double yfov_degrees = 0.0, ymag = 0.0;
  bool ok = kind == "perspective" || kind == "orthographic";
  int found = 0;
  while (ok && in >> key >> value) {
    if (key == "eye")
      eye = parse_vector(value, &ok), found |= 1;
    else if (key == "target")
      target = parse_vector(value, &ok), found |= 2;
    else if (key == "up")
      up = parse_vector(value, &ok), found |= 4;
    else if (key == "yfov_degrees")
      yfov_degrees = std::strtod(value.c_str(), nullptr), found |= 8;
    else if (key == "ymag")
      ymag = std::strtod(value.c_str(), nullptr), found |= 16;
  }
  ViewCamera c;
  c.orthographic = kind == "orthographic";
  const bool lens =
      c.orthographic ? (found & 16) && ymag > 0.0 : (found & 8) && yfov_degrees > 0.0 && yfov_degrees < 180.0;
  c.eye = eye;
  c.forward = target - eye;
  if (!ok || (found & 7) != 7 || !lens || !(glm::length(c.forward) > 0.0) || !(glm::length(up) > 0.0))
    throw Error(source + ": its rcsplat:camera attribute is not a view rcsplat wrote ('" + attribute.substr(0, 80) +
                "')");
  c.forward = glm::normalize(c.forward);
  c.right = glm::cross(c.forward, glm::normalize(up));
  if (!(glm::length(c.right) > 1e-9)) throw Error(source + ": its rcsplat:camera's up is along the view");
  c.right = glm::normalize(c.right);
  c.up = glm::cross(c.right, c.forward);
  c.tan_half_fov_y = std::tan(0.5 * yfov_degrees * std::numbers::pi / 180.0);
  c.half_height = ymag;
  return c;
}

SequenceFrame read_sequence_frame(const std::string& path, const std::string& layer, const std::string& geometry_path,
                                  bool demodulate) {
  // Each file is read once: the colours' (and albedo's), and the geometry's when another file holds it.
  const ExrPixels image = read_exr_file(path);
  const std::string& geometry_name = geometry_path.empty() ? path : geometry_path;
  const ExrPixels other = geometry_path.empty() ? ExrPixels{} : read_exr_file(geometry_path);
  const ExrPixels& geometry = geometry_path.empty() ? image : other;
  SequenceFrame f;
  auto camera = geometry.text.find("rcsplat:camera");
  if (camera == geometry.text.end())
    throw Error(geometry_name + ": has no rcsplat:camera attribute (not a frame rcsplat rendered)");
  f.camera = parse_view_camera(camera->second, geometry_name);
  f.width = image.width;
  f.height = image.height;
  f.rgb = exr_channels(image, path, layer, {"R", "G", "B"});
  if (geometry.width != f.width || geometry.height != f.height)
    throw Error(geometry_name + ": not the size of " + path);
  f.position = exr_channels(geometry, geometry_name, "position", {"X", "Y", "Z"});
  f.depth = exr_channels(geometry, geometry_name, "depth", {"Z"});
  if (demodulate) divide_by_albedo(f.rgb, exr_channels(image, path, "albedo", {"R", "G", "B"}));
  return f;
}

void divide_by_albedo(std::vector<float>& rgb, const std::vector<float>& albedo) {
  for (size_t i = 0; i < rgb.size(); ++i)
    rgb[i] = albedo[i] >= 0.02f ? rgb[i] / albedo[i] : std::numeric_limits<float>::quiet_NaN();
}

TemporalError temporal_rel_mse(const SequenceFrame& earlier, const SequenceFrame& later) {
  if (earlier.width != later.width || earlier.height != later.height)
    throw Error("flicker: the frames differ in size (" + std::to_string(earlier.width) + " x " +
                std::to_string(earlier.height) + " and " + std::to_string(later.width) + " x " +
                std::to_string(later.height) + ")");
  const int w = earlier.width, h = earlier.height;
  const ViewCamera& c = earlier.camera;
  const double aspect = double(w) / double(h);
  double sum = 0.0;
  TemporalError out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      if (!(later.depth[p] > 0.0f)) continue;
      ++out.hits;
      const glm::dvec3 point(later.position[3 * p], later.position[3 * p + 1], later.position[3 * p + 2]);
      const glm::dvec3 d = point - c.eye;
      const double z = glm::dot(d, c.forward);
      // Screen coordinates in [-1, 1], as the G-buffer's rays are made (kernels/gbuffer.cl), then the pixel.
      const double half_y = c.orthographic ? c.half_height : z * c.tan_half_fov_y;
      if (!c.orthographic && !(z > 0.0)) continue;
      const double sx = glm::dot(d, c.right) / (half_y * aspect), sy = glm::dot(d, c.up) / half_y;
      const double fx = (sx + 1.0) * 0.5 * w, fy = (1.0 - sy) * 0.5 * h;
      if (!(fx >= 0.0 && fx < w && fy >= 0.0 && fy < h)) continue;
      const size_t q = size_t(fy) * size_t(w) + size_t(fx);
      if (!(earlier.depth[q] > 0.0f)) continue;
      // The same surface: the earlier pixel's point within a few pixel footprints of this one (else it was hidden).
      const glm::dvec3 seen(earlier.position[3 * q], earlier.position[3 * q + 1], earlier.position[3 * q + 2]);
      const double footprint = 2.0 * half_y / h;
      if (!(glm::length(seen - point) <= 4.0 * footprint)) continue;
      bool finite = true;
      for (int k = 0; k < 3; ++k)
        finite = finite && std::isfinite(later.rgb[3 * p + size_t(k)]) && std::isfinite(earlier.rgb[3 * q + size_t(k)]);
      if (!finite) continue;
      for (int k = 0; k < 3; ++k) {
        const double a = later.rgb[3 * p + size_t(k)], b = earlier.rgb[3 * q + size_t(k)], m = 0.5 * (a + b);
        sum += 0.5 * (a - b) * (a - b) / (m * m + kRelMseOffset);
      }
      ++out.pixels;
    }
  out.rel_mse = out.pixels ? sum / (3.0 * double(out.pixels)) : 0.0;
  return out;
}

}  // namespace rcsplat
