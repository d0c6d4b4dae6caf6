#include "render/render_output.h"

#include "util/error.h"
#include "util/paths.h"

namespace rcsplat {

void write_render(const std::string& path, const RenderedImage& image, float exposure_stops,
                  const ExrAttributes& attributes) {
  std::string ext = lower_extension(path);
  if (!is_output_format(path)) throw Error(path + ": unknown output format '" + ext + "' (use " + output_formats() + ")");
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
  }
}

}  // namespace rcsplat
