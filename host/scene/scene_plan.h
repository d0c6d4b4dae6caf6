// What a scene contains and what rcsplat will simulate for it (issue 11): `rcsplat info`, the render summary and its
// JSON all print this. scene_switches is also what DeviceScene compiles the kernels with: the one place that decides
// the coarse -D switches, so what `info` reports is what a render compiles.
#pragma once
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "kernels/shared_types.h"
#include "scene/packed_scene.h"
#include "scene/scene.h"

namespace rcsplat {

// The scene's kernel switches (name -> "1" or "0"): HAS_TEXTURES, HAS_VERTEX_COLORS, HAS_ALPHA_MASK,
// HAS_SPECULAR_BRDF (any non-Lambertian material), HAS_PUNCTUAL_LIGHTS, HAS_EMITTERS, HAS_ENVIRONMENT,
// HAS_NORMAL_MAPS, HAS_EMISSIVE_TEXTURES (an emitter whose emission is textured), HAS_TRANSMISSION (glass), HAS_LAYERS
// (clearcoat, sheen, specular colour). Those named in `forced` are on
// whatever the scene holds: tests show that compiling a feature the scene does not use changes no bit of its image.
// The BVH adds BVH_STACK_SIZE, passes their own (STORE_STRATA, ...).
std::map<std::string, std::string> scene_switches(const PackedScene& packed, bool has_vertex_colors,
                                                  const std::set<std::string>& forced = {});

struct MaterialPlan {
  std::string name;
  int lobe = LOBE_NONE;  // LOBE_*: how the cache shades its specular lobe
  float metallic = 0, roughness = 1;
  bool emissive = false, textured = false;
  bool normal_mapped = false;      // its normal map shades (HAS_NORMAL_MAPS)
  bool emissive_textured = false;  // its emission is textured, sampled by textured power (HAS_EMISSIVE_TEXTURES)
  bool glass = false;        // it transmits (HAS_TRANSMISSION, kernels/glass.h)
  bool thin_walled = false;  // glass without a volume: rays pass it straight
  // Its layers (HAS_LAYERS, kernels/brdf_layers.h): a clearcoat, a sheen, a specular colour.
  bool clearcoat = false, sheen = false, specular_colour = false;
};

struct ScenePlan {
  std::string source;
  size_t triangles = 0, emissive_triangles = 0, textures = 0;
  bool vertex_colors = false, alpha_mask = false, alpha_blend = false;
  unsigned normal_mapped_materials = 0, emissive_textured_materials = 0, glass_materials = 0, layered_materials = 0;
  std::vector<MaterialPlan> materials;
  std::array<unsigned, LOBE_KINDS> lobe_counts{};
  unsigned point_lights = 0, spot_lights = 0, directional_lights = 0;
  // The environment (scene/environment.h): its description ("" for none), and the share of its power in the peak that
  // shadow rays sample.
  std::string environment;
  bool environment_map = false;
  int environment_width = 0, environment_height = 0;
  float environment_intensity = 1, environment_rotation_degrees = 0;
  double environment_peak_fraction = 0, environment_mean_luminance = 0;
  std::vector<std::string> not_simulated;  // the loader's notes: what the file asks for and what rcsplat does instead
  std::map<std::string, std::string> switches;
  // What rcsplat does with each kind of material, and whether it compiles radiance caching (LOBE_HSH present).
  bool radiance_cache() const { return lobe_counts[LOBE_HSH] > 0; }
};

ScenePlan plan_scene(const Scene& scene);

// How the cache methods shade a material of this LOBE_*, in a few words (for `info` and the summary).
const char* lobe_treatment(int lobe);
// How the cache methods shade this material: its kind's treatment, or glass's, or a layered material's.
const char* material_treatment(const MaterialPlan& m);
const char* lobe_name(int lobe);

}  // namespace rcsplat
