// Writing images: EXR (linear float, with the render's layers) and PNG (tone-mapped, sRGB). A file appears only when
// complete: it is written under a temporary name and renamed.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace rcsplat {

struct ImageLayer {
  std::string name;  // "" for the main RGB
  std::vector<std::string> channels;  // e.g. {"R", "G", "B"}
  const std::vector<float>* data;     // channels.size() floats a pixel
};

// Metadata stored in an EXR's header as strings ("rcsplat:path_samples" and the like).
using ExrAttributes = std::map<std::string, std::string>;

void write_exr(const std::string& path, int width, int height, const std::vector<ImageLayer>& layers,
               const ExrAttributes& attributes = {});
// Exposure in stops, then a filmic curve (Narkowicz's ACES fit) and the sRGB transfer function.
void write_png(const std::string& path, int width, int height, const std::vector<float>& rgb, float exposure_stops);
// Display values in [0, 1] straight to 8 bits (false-colour images).
void write_png_display(const std::string& path, int width, int height, const std::vector<float>& rgb);

// False in a build without OpenImageIO (RCSPLAT_WITH_OPENIMAGEIO=OFF): then PNG functions throw rcsplat::Error, and
// EXR files are written uncompressed and read only when uncompressed (exr_file.h).
bool have_openimageio();
// The extensions write_render (render/render_output.h) accepts in this build, for messages (".exr or .png").
std::string output_formats();
// Whether write_render can write this path (.exr or .png, any case).
bool is_output_format(const std::string& path);

// The string attributes of an EXR whose names start with "rcsplat:".
ExrAttributes read_exr_attributes(const std::string& path);

// Reads an EXR's main RGB (R, G, B channels) for comparisons. Throws rcsplat::Error on failure.
std::vector<float> read_exr_rgb(const std::string& path, int& width, int& height);
// The same for a layer's R, G, B channels ("indirect" reads indirect.R, indirect.G, indirect.B).
std::vector<float> read_exr_layer(const std::string& path, const std::string& layer, int& width, int& height);
// Any channels of a layer, in the order named: {"X", "Y", "Z"} of "position" reads position.X, .Y, .Z.
std::vector<float> read_exr_channels(const std::string& path, const std::string& layer,
                                     const std::vector<std::string>& names, int& width, int& height);
bool exr_has_layer(const std::string& path, const std::string& layer);

}  // namespace rcsplat
