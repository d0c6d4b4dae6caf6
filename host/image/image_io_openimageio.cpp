// The image formats through OpenImageIO: EXR (zip-compressed on writing, any EXR on reading) and PNG. Built when
// RCSPLAT_WITH_OPENIMAGEIO is on (the default); image_io_without_openimageio.cpp replaces it otherwise.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "image/exr_file.h"
#include "image/image_io.h"
#include "image/tone_map.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace rcsplat {
namespace {

// Writes through OpenImageIO, atomically (util/atomic_file.h).
void write_pixels(const std::string& path, const OIIO::ImageSpec& spec, const void* pixels) {
  write_file_atomically(path, [&](const std::string& temp) -> std::string {
    auto out = OIIO::ImageOutput::create(temp);
    if (!out) return "cannot write this image format: " + OIIO::geterror();
    if (!out->open(temp, spec)) return "cannot open for writing: " + out->geterror();
    bool ok = out->write_image(spec.format, pixels);
    ok = out->close() && ok;
    return ok ? "" : "writing failed: " + out->geterror();
  });
}

}  // namespace

bool have_openimageio() { return true; }

void write_exr_file(const std::string& path, const ExrPixels& image) {
  OIIO::ImageSpec spec(image.width, image.height, int(image.channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  spec.attribute("compression", "zip");
  // OpenImageIO stamps the current time into a file without a DateTime: an empty one keeps the bytes reproducible.
  spec.attribute("DateTime", "");
  for (const auto& [name, value] : image.text) spec.attribute(name, value);
  write_pixels(path, spec, image.values.data());
}

namespace {

// Opens path and copies its header into *image; the caller reads the pixels if it wants them.
std::unique_ptr<OIIO::ImageInput> open_exr(const std::string& path, ExrPixels* image) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot be read: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  image->width = spec.width;
  image->height = spec.height;
  image->channels = spec.channelnames;
  for (const OIIO::ParamValue& p : spec.extra_attribs)
    if (p.type() == OIIO::TypeDesc::STRING) image->text[p.name().string()] = p.get_string();
  return in;
}

}  // namespace

ExrPixels read_exr_header(const std::string& path) {
  ExrPixels image;
  open_exr(path, &image);
  return image;
}

ExrPixels read_exr_file(const std::string& path) {
  ExrPixels image;
  auto in = open_exr(path, &image);
  int channels = int(image.channels.size());
  image.values.resize(size_t(image.width) * size_t(image.height) * size_t(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, image.values.data()))
    throw Error(path + ": cannot be read: " + in->geterror());
  return image;
}

void write_png(const std::string& path, int width, int height, const std::vector<float>& rgb, float exposure_stops) {
  std::vector<float> display = display_image(rgb, exposure_stops);
  std::vector<uint8_t> bytes(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) bytes[i] = uint8_t(std::lround(255.0f * display[i]));
  write_pixels(path, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8), bytes.data());
}

void write_png_display(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  std::vector<uint8_t> bytes(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i)
    bytes[i] = uint8_t(std::lround(255.0f * std::clamp(std::isfinite(rgb[i]) ? rgb[i] : 0.0f, 0.0f, 1.0f)));
  write_pixels(path, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8), bytes.data());
}

}  // namespace rcsplat
