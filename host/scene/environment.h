// Light from outside the scene: a uniform sky or an equirectangular HDR map (kernels/environment.h draws it). Given
// on the command line (--sky, --environment), it belongs to the Scene like its lights.
#pragma once
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>


namespace rcsplat {

// How light from the light sources passes glass (--light-through-glass, docs/ALGORITHM.md section 12): a lighting
// setting that, like the environment, belongs to the Scene once it loads and sets the kernels' switches.
struct GlassLight {
  // false (straight, the default): shadow rays pass every glass straight with its colour. true (caustics): a glass
  // volume stops shadow rays, and the light it passes comes by the glass caustic map; thin-walled glass still passes
  // shadow rays, which is exact for it.
  bool caustics = false;
  // --glass-caustic-photons: photon paths shot for the glass caustic map, aimed at the volumes (most land past one).
  unsigned photons = 1u << 18;
  unsigned neighbours = 64;     // photons its gather radius holds on average where they crowd
};

// What the command line asks for: a sky colour or a map file (not both), its intensity and rotation about +Y.
struct EnvironmentSettings {
  std::optional<glm::vec3> sky;  // --sky R,G,B: uniform radiance
  std::string file;              // --environment FILE (.exr, .hdr, anything OpenImageIO reads)
  float intensity = 1.0f;        // --environment-intensity: multiplies the map
  float rotation_degrees = 0.0f;  // --environment-rotation: about +Y, counter-clockwise seen from above
  GlassLight glass;  // not light from outside, but given and applied with it when the scene loads
  bool requested() const { return sky.has_value() || !file.empty(); }
};


// Texels brighter than this many times the map's mean luminance give their excess to the peak, which shadow rays
// sample; the rest is gathered by the cache's rays (kernels/environment.h). A sun is 10^3 to 10^5 times the mean; an
// overcast sky's brightest zenith about 3 times.
constexpr double kEnvironmentPeakOverMean = 4.0;

struct Environment {
  // Equirectangular radiance (intensity applied), rows from +Y (theta = 0) down, columns from -Z through +X (Mitsuba's
  // convention). A uniform sky is one texel. Empty: no environment.
  int width = 0, height = 0;
  std::vector<glm::vec3> radiance;
  float rotation_degrees = 0.0f;
  std::string source;  // the file, or "" for a uniform sky
  float intensity = 1.0f;

  bool present() const { return width > 0; }
  // For `info` and the summary: "uniform sky (0.5, 0.6, 0.8)" or "sky.exr (2048 x 1024, intensity 1, rotated 90°)".
  std::string describe() const;
};

// Throws rcsplat::Error naming the option or the file: a sky colour must be finite and non-negative, a map must be
// readable with finite non-negative texels, intensity finite and non-negative, rotation finite.
Environment make_environment(const EnvironmentSettings& settings);

// The environment in the kernels' layout: texels (RGB, w = the smooth fraction), the peak's sampling CDFs (the
// marginal over rows, then each row's: height + 1 + height (width + 1) floats) and the SceneCounts fields.
struct PackedEnvironment {
  std::vector<float> texels;  // four per texel: RGB radiance and the smooth fraction
  std::vector<float> cdf;
  unsigned width = 0, height = 0;
  float rotation[2] = {1.0f, 0.0f};  // cos, sin
  float peak_power = 0.0f;           // sum of the peak's luminance times solid angle (0: no peak)
  double peak_fraction = 0.0;        // of the map's power (luminance times solid angle), for the summary
  double mean_luminance = 0.0;
};
PackedEnvironment pack_environment(const Environment& environment);

// "(r, g, b)" for messages and descriptions.
std::string format_rgb(const glm::vec3& c);

// A texel row's solid angle (all of its width): 2 pi (cos(pi j / h) - cos(pi (j + 1) / h)).
double environment_row_solid_angle(int row, int height);

}  // namespace rcsplat
