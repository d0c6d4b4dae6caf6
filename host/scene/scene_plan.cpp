#include "scene/scene_plan.h"

#include <algorithm>

namespace rcsplat {

std::map<std::string, std::string> scene_switches(const PackedScene& p, bool has_vertex_colors,
                                                  const std::set<std::string>& forced) {
  bool textured = false, masked = false, specular = false, normal_maps = false, emissive_textures = false,
       glass = false, layers = false, glass_volume = false;
  for (const Material& m : p.materials) {
    // Every texture a material reads through HAS_TEXTURES's code: base colour, metallic-roughness, specular, layers.
    textured |= m.base_color_texture >= 0 || m.metallic_roughness_texture >= 0 || m.specular_texture >= 0;
    textured |= m.layered && (m.specular_color_texture >= 0 || m.clearcoat_texture >= 0 ||
                              m.clearcoat_roughness_texture >= 0 || m.sheen_color_texture >= 0 ||
                              m.sheen_roughness_texture >= 0 || m.clearcoat_normal_texture >= 0);
    masked |= m.alpha_cutoff > 0.0f || m.alpha_blend;
    specular |= m.lobe != LOBE_NONE;
    normal_maps |= (m.normal_texture >= 0 || (m.layered && m.clearcoat_normal_texture >= 0)) && !p.tangents.empty();
    layers |= m.layered != 0;
    glass |= m.transmission > 0.0f && m.metallic < 1.0f;
    glass_volume |= m.transmission > 0.0f && m.metallic < 1.0f && m.thickness > 0.0f;
  }
  for (const EmissiveTriangle& e : p.emitters) emissive_textures |= emitter_textured_triangle(e) >= 0;
  std::map<std::string, std::string> switches;
  auto set = [&](const char* name, bool on) { switches[name] = on || forced.count(name) ? "1" : "0"; };
  set("HAS_TEXTURES", textured);
  set("HAS_VERTEX_COLORS", has_vertex_colors);
  set("HAS_ALPHA_MASK", masked);
  set("HAS_SPECULAR_BRDF", specular);
  set("HAS_PUNCTUAL_LIGHTS", !p.lights.empty());
  set("HAS_EMITTERS", !p.emitters.empty());
  set("HAS_ENVIRONMENT", p.environment.width > 0);
  set("HAS_NORMAL_MAPS", normal_maps);
  set("HAS_EMISSIVE_TEXTURES", emissive_textures);
  set("HAS_TRANSMISSION", glass);
  set("HAS_LAYERS", layers);
  // A glass volume's light by the glass caustic map (--light-through-glass caustics; needs HAS_TRANSMISSION).
  switches["HAS_GLASS_CAUSTICS"] = glass && ((glass_volume && p.glass_caustics) || forced.count("HAS_GLASS_CAUSTICS"))
                                       ? "1"
                                       : "0";
  // Tests only: the environment's peak sampled uniformly over the sphere, to check its importance sampling against.
  if (forced.count("ENVIRONMENT_UNIFORM_SAMPLING")) switches["ENVIRONMENT_UNIFORM_SAMPLING"] = "1";
  return switches;
}

const char* lobe_name(int lobe) {
  switch (lobe) {
    case LOBE_NONE: return "Lambertian";
    case LOBE_ROUGH: return "rough";
    case LOBE_GLOSSY: return "glossy";
    case LOBE_HSH: return "radiance-cached";
    default: return "unknown";
  }
}

const char* material_treatment(const MaterialPlan& m) {
  if (m.glass) return "seen through and passed by every ray, never cached (the share that is not glass as its kind says)";
  if (m.clearcoat || m.sheen || m.specular_colour) {
    if (m.lobe == LOBE_GLOSSY)
      return "diffuse base from the cached irradiance; its lobes (base, coat, sheen) sampled per pixel (layered: never "
             "radiance-cached)";
    if (m.lobe == LOBE_ROUGH)
      return "diffuse base, and its lobes' albedo (base, coat, sheen) times the cached irradiance";
  }
  return lobe_treatment(m.lobe);
}

const char* lobe_treatment(int lobe) {
  switch (lobe) {
    case LOBE_NONE: return "albedo / pi times the cached irradiance (exact)";
    case LOBE_ROUGH: return "diffuse base and the lobe's albedo times the cached irradiance";
    case LOBE_GLOSSY: return "diffuse base from the cached irradiance; the lobe sampled per pixel (too sharp for HSH)";
    case LOBE_HSH: return "diffuse base from the cached irradiance; the lobe from HSH radiance records";
    default: return "";
  }
}

ScenePlan plan_scene(const Scene& scene) {
  const PackedScene packed = pack_scene(scene, {}, Texels::left_out);
  ScenePlan plan;
  plan.source = scene.source;
  plan.triangles = scene.triangle_count();
  plan.emissive_triangles = packed.emitters.size();
  plan.textures = scene.textures.size();
  plan.vertex_colors = scene.has_vertex_colors();
  for (size_t i = 0; i < packed.materials.size(); ++i) {
    const Material& m = packed.materials[i];
    const SceneMaterial& source = scene.materials[i];
    MaterialPlan mp;
    mp.name = source.name.empty() ? "material " + std::to_string(i) : source.name;
    mp.lobe = m.lobe;
    mp.metallic = m.metallic;
    mp.roughness = m.roughness;
    mp.emissive = m.emission[0] > 0.0f || m.emission[1] > 0.0f || m.emission[2] > 0.0f;
    mp.textured = m.base_color_texture >= 0 || source.metallic_roughness_texture >= 0 || source.specular_texture >= 0;
    mp.normal_mapped = m.normal_texture >= 0 && !packed.tangents.empty();
    mp.emissive_textured = mp.emissive && m.emissive_texture >= 0;
    mp.glass = m.transmission > 0.0f && m.metallic < 1.0f;
    mp.thin_walled = mp.glass && !(m.thickness > 0.0f);
    if (m.layered) {
      mp.clearcoat = m.clearcoat > 0.0f;
      mp.sheen = std::max({m.sheen_color[0], m.sheen_color[1], m.sheen_color[2]}) > 0.0f;
      mp.specular_colour = source.specular_color != glm::vec3(1.0f) || source.specular_color_texture >= 0;
      plan.layered_materials += 1;
    }
    plan.glass_materials += mp.glass;
    plan.normal_mapped_materials += mp.normal_mapped;
    plan.emissive_textured_materials += mp.emissive_textured;
    plan.alpha_mask |= m.alpha_cutoff > 0.0f;
    plan.alpha_blend |= m.alpha_blend != 0;
    ++plan.lobe_counts[size_t(m.lobe)];
    plan.materials.push_back(mp);
  }
  for (const SceneLight& l : scene.lights) {
    plan.point_lights += l.type == LightType::point;
    plan.spot_lights += l.type == LightType::spot;
    plan.directional_lights += l.type == LightType::directional;
  }
  if (scene.environment.present()) {
    const Environment& e = scene.environment;
    plan.environment = e.describe();
    plan.environment_map = !e.source.empty();
    plan.environment_width = e.width;
    plan.environment_height = e.height;
    plan.environment_intensity = e.intensity;
    plan.environment_rotation_degrees = e.rotation_degrees;
    plan.environment_peak_fraction = packed.environment.peak_fraction;
    plan.environment_mean_luminance = packed.environment.mean_luminance;
  }
  plan.not_simulated = scene.unsupported;
  const bool volume = std::any_of(plan.materials.begin(), plan.materials.end(),
                                  [](const MaterialPlan& m) { return m.glass && !m.thin_walled; });
  if (volume && !scene.glass_light.caustics)
    plan.not_simulated.push_back("focused caustics of glass volumes: shadow rays pass a volume straight with its "
                                 "colour (--light-through-glass caustics focuses its light)");
  plan.switches = scene_switches(packed, plan.vertex_colors);
  return plan;
}

}  // namespace rcsplat
