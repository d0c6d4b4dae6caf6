// A build without OpenImageIO (RCSPLAT_WITH_OPENIMAGEIO=OFF) for machines that lack its codec libraries, such as a lent
// GPU machine (docs/GPU.md): EXR goes through rcsplat's own uncompressed writer and reader, PNG fails with a clear error.
#include "image/exr_file.h"
#include "image/image_io.h"
#include "util/error.h"

namespace rcsplat {

bool have_openimageio() { return false; }

void write_exr_file(const std::string& path, const ExrPixels& image) { write_uncompressed_exr(path, image); }
ExrPixels read_exr_file(const std::string& path) { return read_uncompressed_exr(path); }
ExrPixels read_exr_header(const std::string& path) { return read_uncompressed_exr(path, false); }

void write_png(const std::string& path, int, int, const std::vector<float>&, float) {
  throw Error(path + ": PNG needs OpenImageIO, and this rcsplat was built without it (RCSPLAT_WITH_OPENIMAGEIO=OFF)");
}
void write_png_display(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  write_png(path, width, height, rgb, 0.0f);
}

}  // namespace rcsplat
