#include "image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "util/error.h"
#include "util/paths.h"

namespace rcsplat {
namespace fs = std::filesystem;
namespace {

// Writes through OpenImageIO to a temporary file beside the target, then renames it into place.
void write_pixels(const std::string& path, OIIO::ImageSpec spec, const void* pixels) {
  fs::path target(path);
  fs::path temp = target.parent_path() / ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) +
                                          target.extension().string());
  auto out = OIIO::ImageOutput::create(temp.string());
  if (!out) throw Error(path + ": cannot write this image format: " + OIIO::geterror());
  if (!out->open(temp.string(), spec)) throw Error(path + ": cannot open for writing: " + out->geterror());
  bool ok = out->write_image(spec.format, pixels);
  ok = out->close() && ok;
  std::error_code ec;
  if (!ok) {
    fs::remove(temp, ec);
    throw Error(path + ": writing failed: " + out->geterror());
  }
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw Error(path + ": cannot move the finished image into place: " + ec.message());
  }
}

float tone_map(float x) {
  // Narkowicz 2015, a fit of the ACES filmic curve.
  x = std::max(x, 0.0f);
  return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

float srgb_encode(float x) { return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f; }

}  // namespace

void write_exr(const std::string& path, int width, int height, const std::vector<ImageLayer>& layers,
               const ExrAttributes& attributes) {
  size_t pixels = size_t(width) * size_t(height);
  std::vector<std::string> names;
  for (const ImageLayer& l : layers)
    for (const std::string& c : l.channels) names.push_back(l.name.empty() ? c : l.name + "." + c);
  std::vector<float> interleaved(pixels * names.size());
  size_t offset = 0;
  for (const ImageLayer& l : layers) {
    size_t n = l.channels.size();
    for (size_t i = 0; i < pixels; ++i)
      for (size_t c = 0; c < n; ++c) {
        float v = (*l.data)[i * n + c];
        interleaved[i * names.size() + offset + c] = std::isfinite(v) ? v : 0.0f;  // every pixel finite
      }
    offset += n;
  }
  OIIO::ImageSpec spec(width, height, int(names.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.attribute("compression", "zip");
  spec.attribute("Software", "rcsplat " RCSPLAT_VERSION);
  for (const auto& [name, value] : attributes) spec.attribute(name, value);
  write_pixels(path, spec, interleaved.data());
}

void write_png(const std::string& path, int width, int height, const std::vector<float>& rgb, float exposure_stops) {
  float scale = std::exp2(exposure_stops);
  std::vector<uint8_t> bytes(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    float v = std::isfinite(rgb[i]) ? rgb[i] : 0.0f;
    bytes[i] = uint8_t(std::lround(255.0f * srgb_encode(tone_map(v * scale))));
  }
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  write_pixels(path, spec, bytes.data());
}

void write_png_display(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  std::vector<uint8_t> bytes(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i)
    bytes[i] = uint8_t(std::lround(255.0f * std::clamp(std::isfinite(rgb[i]) ? rgb[i] : 0.0f, 0.0f, 1.0f)));
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  write_pixels(path, spec, bytes.data());
}

bool is_output_format(const std::string& path) {
  std::string ext = lower_extension(path);
  return ext == ".png" || ext == ".exr";
}

void write_render(const std::string& path, const RenderedImage& image, float exposure_stops,
                  const ExrAttributes& attributes) {
  std::string ext = lower_extension(path);
  if (ext == ".png") {
    write_png(path, image.width, image.height, image.color, exposure_stops);
  } else if (ext == ".exr") {
    std::vector<std::string> rgb = {"R", "G", "B"};
    std::vector<ImageLayer> layers = {{"", rgb, &image.color},
                                      {"direct", rgb, &image.direct},
                                      {"emission", rgb, &image.emission},
                                      {"albedo", rgb, &image.albedo},
                                      {"normal", {"X", "Y", "Z"}, &image.normal},
                                      {"position", {"X", "Y", "Z"}, &image.position},
                                      {"depth", {"Z"}, &image.depth}};
    // Global illumination layers, present when the render computed them.
    auto add = [&](const char* name, std::vector<std::string> channels, const std::vector<float>& data) {
      if (!data.empty()) layers.push_back({name, std::move(channels), &data});
    };
    add("indirect", rgb, image.indirect);
    add("irradiance", rgb, image.irradiance);
    add("indirect_variance", rgb, image.indirect_variance);
    add("coverage", {"Y"}, image.coverage);
    add("records", {"Y"}, image.records_per_pixel);
    add("record_positions", {"Y"}, image.record_positions);
    write_exr(path, image.width, image.height, layers, attributes);
  } else {
    throw Error(path + ": unknown output format '" + ext + "' (use .exr or .png)");
  }
}

std::vector<float> read_exr_layer(const std::string& path, const std::string& layer, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot be read: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::string prefix = layer.empty() ? "" : layer + ".";
  int channel[3] = {-1, -1, -1};
  for (int c = 0; c < spec.nchannels; ++c)
    for (int k = 0; k < 3; ++k)
      if (spec.channelnames[size_t(c)] == prefix + std::string(1, "RGB"[k])) channel[k] = c;
  if (channel[0] < 0 || channel[1] < 0 || channel[2] < 0)
    throw Error(path + ": has no " + prefix + "R, " + prefix + "G, " + prefix + "B channels");
  std::vector<float> all(size_t(width) * size_t(height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
    throw Error(path + ": cannot be read: " + in->geterror());
  std::vector<float> rgb(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
    for (int k = 0; k < 3; ++k) rgb[i * 3 + size_t(k)] = all[i * size_t(spec.nchannels) + size_t(channel[k])];
  return rgb;
}

std::vector<float> read_exr_rgb(const std::string& path, int& width, int& height) {
  return read_exr_layer(path, "", width, height);
}

ExrAttributes read_exr_attributes(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot be read: " + OIIO::geterror());
  ExrAttributes out;
  for (const OIIO::ParamValue& p : in->spec().extra_attribs) {
    std::string name = p.name().string();
    if (name.rfind("rcsplat:", 0) == 0) out[name] = p.get_string();
  }
  return out;
}

bool exr_has_layer(const std::string& path, const std::string& layer) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot be read: " + OIIO::geterror());
  for (const std::string& name : in->spec().channelnames)
    if (name == layer + ".R") return true;
  return false;
}

}  // namespace rcsplat
