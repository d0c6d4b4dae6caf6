// EXR layers and attributes on top of the build's EXR implementation (exr_file.h), and choosing an output format by
// extension. PNG and the EXR implementations are in image_io_openimageio.cpp or image_io_without_openimageio.cpp.
#include "image/image_io.h"

#include <cmath>
#include <cstdlib>
#include <ctime>

#include "image/exr_file.h"
#include "util/error.h"
#include "util/paths.h"

namespace rcsplat {

std::string output_formats() { return have_openimageio() ? ".exr or .png" : ".exr (this build has no PNG)"; }

bool is_output_format(const std::string& path) {
  std::string ext = lower_extension(path);
  return ext == ".exr" || (have_openimageio() && ext == ".png");
}

void write_exr(const std::string& path, int width, int height, const std::vector<ImageLayer>& layers,
               const ExrAttributes& attributes) {
  ExrPixels image{width, height, {}, {}, attributes};
  image.text["Software"] = "rcsplat " RCSPLAT_VERSION;
  // Same input, same bytes: the file carries no clock time unless the build asks for one (reproducible-builds.org's
  // SOURCE_DATE_EPOCH, seconds since 1970, written in EXR's capDate form, UTC).
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    long long seconds = std::strtoll(epoch, &end, 10);
    std::time_t t = std::time_t(seconds);
    std::tm utc{};
    char stamp[32];
    if (*epoch && *end == 0 && seconds >= 0 && gmtime_r(&t, &utc) &&
        std::strftime(stamp, sizeof stamp, "%Y:%m:%d %H:%M:%S", &utc))
      image.text["DateTime"] = stamp;
  }
  for (const ImageLayer& l : layers)
    for (const std::string& c : l.channels) image.channels.push_back(l.name.empty() ? c : l.name + "." + c);
  size_t pixels = size_t(width) * size_t(height), stride = image.channels.size();
  image.values.resize(pixels * stride);
  size_t offset = 0;
  for (const ImageLayer& l : layers) {
    size_t n = l.channels.size();
    for (size_t i = 0; i < pixels; ++i)
      for (size_t c = 0; c < n; ++c) {
        float v = (*l.data)[i * n + c];
        image.values[i * stride + offset + c] = std::isfinite(v) ? v : 0.0f;  // every pixel finite
      }
    offset += n;
  }
  write_exr_file(path, image);
}

std::vector<float> read_exr_channels(const std::string& path, const std::string& layer,
                                     const std::vector<std::string>& names, int& width, int& height) {
  const ExrPixels image = read_exr_file(path);
  width = image.width;
  height = image.height;
  return exr_channels(image, path, layer, names);
}

std::vector<float> exr_channels(const ExrPixels& image, const std::string& path, const std::string& layer,
                                const std::vector<std::string>& names) {
  const int width = image.width, height = image.height;
  const std::string prefix = layer.empty() ? "" : layer + ".";
  const size_t stride = image.channels.size(), n = names.size();
  std::vector<size_t> channel(n, stride);
  for (size_t c = 0; c < stride; ++c)
    for (size_t k = 0; k < n; ++k)
      if (image.channels[c] == prefix + names[k]) channel[k] = c;
  for (size_t k = 0; k < n; ++k)
    if (channel[k] == stride) {
      std::string list;
      for (const std::string& name : names) list += (list.empty() ? "" : ", ") + prefix + name;
      throw Error(path + ": has no " + list + " channels");
    }
  std::vector<float> out(size_t(width) * size_t(height) * n);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
    for (size_t k = 0; k < n; ++k) out[i * n + k] = image.values[i * stride + channel[k]];
  return out;
}

std::vector<float> read_exr_layer(const std::string& path, const std::string& layer, int& width, int& height) {
  return read_exr_channels(path, layer, {"R", "G", "B"}, width, height);
}

std::vector<float> read_exr_rgb(const std::string& path, int& width, int& height) {
  return read_exr_layer(path, "", width, height);
}

ExrAttributes read_exr_attributes(const std::string& path) {
  ExrAttributes out;
  for (const auto& [name, value] : read_exr_header(path).text)
    if (name.rfind("rcsplat:", 0) == 0) out[name] = value;
  return out;
}

bool exr_has_layer(const std::string& path, const std::string& layer) {
  for (const std::string& name : read_exr_header(path).channels)
    if (name == layer + ".R") return true;
  return false;
}

}  // namespace rcsplat
