// An EXR file as rcsplat reads and writes it: float channels, interleaved, and string attributes. Two implementations:
// OpenImageIO's (zip-compressed; any EXR on reading) in image_io_openimageio.cpp, and a small one of rcsplat's own
// (uncompressed scanlines) in exr_uncompressed.cpp, used by a build without OpenImageIO and tested against OpenImageIO.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace rcsplat {

struct ExrPixels {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;        // "R", "indirect.G", ...
  std::vector<float> values;                // channels.size() floats a pixel, rows top to bottom
  std::map<std::string, std::string> text;  // string attributes ("rcsplat:path_samples" and the like)
};

// The build's EXR implementation. All throw rcsplat::Error naming the file.
void write_exr_file(const std::string& path, const ExrPixels& image);
ExrPixels read_exr_file(const std::string& path);
// Channels of a layer read already, in the order named ({"X", "Y", "Z"} of "position": position.X, .Y, .Z); path names
// the file in the error thrown when one is missing (image/image_io.cpp).
std::vector<float> exr_channels(const ExrPixels& image, const std::string& path, const std::string& layer,
                                const std::vector<std::string>& names);
// Size, channel names and attributes without the pixels (values stays empty).
ExrPixels read_exr_header(const std::string& path);

// rcsplat's own: writes uncompressed float scanlines (channels in the alphabetical order the format requires); reads
// single-part scanline files of that kind (FLOAT channels, no compression) and rejects others, saying why.
void write_uncompressed_exr(const std::string& path, const ExrPixels& image);
ExrPixels read_uncompressed_exr(const std::string& path, bool with_pixels = true);

}  // namespace rcsplat
