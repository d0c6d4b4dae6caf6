// A frame's images written out: the EXR with every layer the frame made, or the tone-mapped PNG. Here rather than in
// image/, which knows images and files but not what a frame holds (docs/ARCHITECTURE.md, layers).
#pragma once
#include <string>
#include <vector>

#include "image/image_io.h"
#include "render/frame.h"

namespace rcsplat {

// Writes the render to a .exr (all layers) or .png (tone-mapped) file chosen by the path's extension.
void write_render(const std::string& path, const RenderedImage& image, float exposure_stops,
                  const ExrAttributes& attributes = {});

// Whether these outputs need the frame's colour alone (every one a .png): RenderSettings::color_only.
bool outputs_need_only_color(const std::vector<std::string>& paths);

}  // namespace rcsplat
