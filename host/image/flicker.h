// Flicker: how much a sequence's light changes from one frame to the next where the same surface is seen in both
// (docs/ALGORITHM.md section 10). Each pixel of the later frame is carried back into the earlier one by its world
// position (the EXR's position layer) and the earlier frame's camera (its rcsplat:camera attribute), and kept where
// the earlier frame sees the same point there; the temporal relMSE is the mean over those pixels and the channels of
//   (a - b)^2 / 2 / (((a + b) / 2)^2 + 0.01),
// so that independent noise of variance s^2 a frame around a value c reads about s^2 / (c^2 + 0.01): a frame's own
// relative variance, the unit of relMSE. A reference sequence's own flicker (its noise, and the resampling of nearest
// pixels) is subtracted by the caller.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace rcsplat {

// A frame's view as rcsplat renders it (render/camera.cpp camera_params): rays through pixel centres.
struct ViewCamera {
  bool orthographic = false;
  glm::dvec3 eye{0.0}, forward{0.0, 0.0, -1.0}, right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0};
  double tan_half_fov_y = 0.0, half_height = 0.0;  // perspective; orthographic
};
// From the "rcsplat:camera" attribute ("perspective eye x,y,z target x,y,z up x,y,z yfov_degrees f ymag m").
// Throws rcsplat::Error naming `source` when it is malformed.
ViewCamera parse_view_camera(const std::string& attribute, const std::string& source);

struct SequenceFrame {
  int width = 0, height = 0;
  std::vector<float> rgb;       // the layer judged
  std::vector<float> position;  // world-space x, y, z a pixel
  std::vector<float> depth;     // 0 where the pixel sees nothing
  ViewCamera camera;
};
// Reads frame `path`: its layer `layer` ("indirect", or "" for the full image), and the position, depth and camera of
// `geometry_path` (the same frame; "": `path` itself; a denoised frame holds only colours). demodulate: the layer
// divided by the frame's albedo layer, channel by channel (not a number where the albedo is below 0.02: such pixels
// are left out), so that textures, which do not flicker but do not reproject exactly either, drop out.
SequenceFrame read_sequence_frame(const std::string& path, const std::string& layer,
                                  const std::string& geometry_path = "", bool demodulate = false);

struct TemporalError {
  double rel_mse = 0.0;
  size_t pixels = 0;  // later-frame pixels also seen in the earlier frame
  size_t hits = 0;    // later-frame pixels that see a surface
};
// rgb over albedo, channel by channel; not a number where the albedo is below 0.02 (left out by temporal_rel_mse).
void divide_by_albedo(std::vector<float>& rgb, const std::vector<float>& albedo);

// Pixels whose values are not finite in either frame are left out.
TemporalError temporal_rel_mse(const SequenceFrame& earlier, const SequenceFrame& later);

}  // namespace rcsplat
