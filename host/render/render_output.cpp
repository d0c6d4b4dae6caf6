#include "render/render_output.h"

#include <algorithm>

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
    std::vector<ImageLayer> layers = {{"", rgb, &image.color}};
    // The layers the frame brought back from the device (a colour-only frame: none; RenderSettings::color_only), and
    // the global illumination layers the render computed.
    auto add = [&](const char* name, std::vector<std::string> channels, const std::vector<float>& data) {
      if (!data.empty()) layers.push_back({name, std::move(channels), &data});
    };
    add("direct", rgb, image.direct);
    add("emission", rgb, image.emission);
    add("albedo", rgb, image.albedo);
    add("normal", {"X", "Y", "Z"}, image.normal);
    add("position", {"X", "Y", "Z"}, image.position);
    add("depth", {"Z"}, image.depth);
    add("indirect", rgb, image.indirect);
    add("irradiance", rgb, image.irradiance);
    add("indirect_variance", rgb, image.indirect_variance);
    add("coverage", {"Y"}, image.coverage);
    add("records", {"Y"}, image.records_per_pixel);
    add("record_positions", {"Y"}, image.record_positions);
    add("glossy", rgb, image.glossy);
    add("noisy", rgb, image.noisy_color);
    add("noisy_direct", rgb, image.noisy_direct);
    add("noisy_indirect", rgb, image.noisy_indirect);
    add("noisy_glossy", rgb, image.noisy_glossy);
    write_exr(path, image.width, image.height, layers, attributes);
  }
}

bool outputs_need_only_color(const std::vector<std::string>& paths) {
  return !paths.empty() &&
         std::all_of(paths.begin(), paths.end(), [](const std::string& p) { return lower_extension(p) == ".png"; });
}

}  // namespace rcsplat
