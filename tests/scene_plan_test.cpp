// What a scene contains and what rcsplat compiles for it (scene/scene_plan.h, `rcsplat info`, issue 11): each
// feature a scene adds turns on its own switch and no other, and the device scene compiles exactly the switches the
// plan reports.
#include <gtest/gtest.h>

#include <algorithm>

#include <set>
#include <string>

#include "bvh/bvh8.h"
#include "cl/device_scene.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "scene/scene_plan.h"
#include "test_support.h"

namespace rcsplat {
namespace {

// The built-in Cornell box with one feature added (or its emitter taken away).
Scene cornell_with(const std::string& feature) {
  Scene s = make_cornell_box();
  if (feature == "point light") {
    SceneLight light;
    light.type = LightType::point;
    light.position = 0.5f * (s.bounds_min() + s.bounds_max());
    light.intensity = glm::vec3(1.0f);
    s.lights.push_back(light);
  } else if (feature == "texture") {
    SceneTexture t;
    t.width = t.height = 2;
    t.rgba.assign(16, 200);
    s.textures.push_back(t);
    s.materials[0].base_color_texture = 0;
  } else if (feature == "normal map") {
    SceneTexture t;
    t.width = t.height = 2;
    t.rgba = {160, 128, 240, 255, 128, 160, 240, 255, 100, 128, 240, 255, 128, 100, 240, 255};
    s.textures.push_back(t);
    s.materials[0].normal_texture = 0;
    s.tangents.assign(s.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  } else if (feature == "emissive texture") {
    SceneTexture t;
    t.width = t.height = 2;
    t.rgba = {255, 255, 255, 255, 40, 40, 40, 255, 200, 100, 50, 255, 255, 255, 255, 255};
    s.textures.push_back(t);
    for (SceneMaterial& m : s.materials)
      if (m.emission != glm::vec3(0.0f)) m.emissive_texture = 0;
  } else if (feature == "glossy material") {
    s.materials[0].metallic = 1.0f;
    s.materials[0].roughness = 0.5f;
  } else if (feature == "glass") {
    s.materials[0].transmission = 1.0f;
  } else if (feature == "glass volume" || feature == "glass volume, caustics") {
    s.materials[0].transmission = 1.0f;
    s.materials[0].thickness = 1.0f;
    s.glass_light.caustics = feature == "glass volume, caustics";
  } else if (feature == "clearcoat") {
    s.materials[0].clearcoat = 1.0f;
  } else if (feature == "alpha mask") {
    s.materials[0].alpha_cutoff = 0.5f;
  } else if (feature == "sky") {
    EnvironmentSettings e;
    e.sky = glm::vec3(0.3f);
    s.environment = make_environment(e);
  } else if (feature == "no emitter") {
    for (SceneMaterial& m : s.materials) m.emission = glm::vec3(0.0f);
  }
  return s;
}

TEST(ScenePlan, EachFeatureTurnsOnItsOwnSwitchAndNoOther) {
  const ScenePlan base = plan_scene(cornell_with(""));
  EXPECT_EQ(base.switches, (std::map<std::string, std::string>{{"HAS_ALPHA_MASK", "0"},
                                                                {"HAS_EMISSIVE_TEXTURES", "0"},
                                                                {"HAS_EMITTERS", "1"},
                                                                {"HAS_ENVIRONMENT", "0"},
                                                                {"HAS_GLASS_CAUSTICS", "0"},
                                                                {"HAS_LAYERS", "0"},
                                                                {"HAS_NORMAL_MAPS", "0"},
                                                                {"HAS_PUNCTUAL_LIGHTS", "0"},
                                                                {"HAS_SPECULAR_BRDF", "0"},
                                                                {"HAS_TEXTURES", "0"},
                                                                {"HAS_TRANSMISSION", "0"},
                                                                {"HAS_VERTEX_COLORS", "0"}}));
  EXPECT_EQ(base.lobe_counts[LOBE_NONE], base.materials.size());
  EXPECT_EQ(base.emissive_triangles, 2u);
  EXPECT_FALSE(base.radiance_cache());
  // A clearcoat is a lobe: it turns on the BRDF's code as well as the layers'.
  const std::pair<const char*, std::set<std::string>> cases[] = {{"point light", {"HAS_PUNCTUAL_LIGHTS"}},
                                                                 {"texture", {"HAS_TEXTURES"}},
                                                                 {"glossy material", {"HAS_SPECULAR_BRDF"}},
                                                                 {"alpha mask", {"HAS_ALPHA_MASK"}},
                                                                 {"sky", {"HAS_ENVIRONMENT"}},
                                                                 {"normal map", {"HAS_NORMAL_MAPS"}},
                                                                 {"emissive texture", {"HAS_EMISSIVE_TEXTURES"}},
                                                                 {"glass", {"HAS_TRANSMISSION"}},
                                                                 {"glass volume", {"HAS_TRANSMISSION"}},
                                                                 {"glass volume, caustics",
                                                                  {"HAS_TRANSMISSION", "HAS_GLASS_CAUSTICS"}},
                                                                 {"clearcoat", {"HAS_LAYERS", "HAS_SPECULAR_BRDF"}},
                                                                 {"no emitter", {"HAS_EMITTERS"}}};
  for (const auto& [feature, flipped] : cases) {
    const ScenePlan plan = plan_scene(cornell_with(feature));
    for (const auto& [name, value] : base.switches)
      EXPECT_EQ(plan.switches.at(name) != value, flipped.count(name) == 1) << feature << ": " << name;
  }
  const ScenePlan glossy = plan_scene(cornell_with("glossy material"));
  EXPECT_TRUE(glossy.radiance_cache()) << "roughness 0.5 metal is radiance-cached";
  EXPECT_EQ(glossy.lobe_counts[LOBE_HSH], 1u);
  EXPECT_EQ(plan_scene(cornell_with("point light")).point_lights, 1u);
  EXPECT_EQ(plan_scene(cornell_with("no emitter")).emissive_triangles, 0u);
  // A volume's caustics are named as not simulated unless --light-through-glass caustics asks for them.
  auto names_caustics = [](const ScenePlan& p) {
    return std::any_of(p.not_simulated.begin(), p.not_simulated.end(),
                       [](const std::string& l) { return l.find("caustics of glass volumes") != std::string::npos; });
  };
  EXPECT_TRUE(names_caustics(plan_scene(cornell_with("glass volume"))));
  EXPECT_FALSE(names_caustics(plan_scene(cornell_with("glass volume, caustics"))));
  EXPECT_FALSE(names_caustics(plan_scene(cornell_with("glass")))) << "thin-walled glass passes shadow rays exactly";
}

// What `info` reports is what a render compiles: the device scene's defines are the plan's switches and the BVH's
// stack size.
TEST(ScenePlan, DeviceSceneCompilesThePlansSwitches) {
  for (const char* feature : {"", "point light", "texture", "glossy material", "alpha mask", "sky", "no emitter",
                              "normal map", "emissive texture", "glass", "glass volume, caustics", "clearcoat"}) {
    const Scene scene = cornell_with(feature);
    const Bvh8 bvh = build_bvh8(scene.positions);
    DeviceScene device(test::gpu(), scene, bvh);
    std::map<std::string, std::string> compiled(device.defines().begin(), device.defines().end());
    EXPECT_EQ(compiled, scene_plan_switches(plan_scene(scene), bvh.depth)) << feature;
  }
}

// The Cornell box lit by a point light at `position` instead of its ceiling.
Scene cornell_under_point_light(const glm::vec3& position) {
  Scene scene = cornell_with("no emitter");
  SceneLight light;
  light.type = LightType::point;
  light.position = position;
  light.intensity = glm::vec3(2.0f);
  scene.lights.push_back(light);
  return scene;
}

// Renders the scene with the cache and the path tracer, plain and with `forced` compiled on: the same bits expected.
void expect_forcing_changes_no_bit(const Scene& scene, const std::set<std::string>& forced, const std::string& names) {
  for (GiMethod gi : {GiMethod::splat, GiMethod::path}) {
    RenderSettings settings = test::one_bounce_one_sample();
    settings.width = settings.height = 32;
    settings.gi = gi;
    settings.path.samples = 4;
    const RenderedImage plain = render(test::gpu(), scene, settings);
    settings.forced_switches = forced;
    const RenderedImage compiled = render(test::gpu(), scene, settings);
    EXPECT_EQ(plain.direct, compiled.direct) << names << gi_method_name(gi);
    EXPECT_EQ(plain.indirect, compiled.indirect) << names << gi_method_name(gi);
    EXPECT_EQ(plain.color, compiled.color) << names << gi_method_name(gi);
  }
}

// Simulate only what a scene calls for, and lose nothing by it: compiling a feature's code for a scene that does not use
// it changes no bit of the image (direct, indirect, colour), for the cache and the path tracer. The unused switches are
// compiled on together (one set of programs a scene instead of one a switch: a fifth of the suite's kernel builds);
// a failure names the set, and forcing each alone finds the culprit. HAS_EMITTERS is tried on the Cornell box lit by
// a point light instead of its ceiling (it has emitters otherwise); HAS_SPECULAR_BRDF has its own test
// (GlobalIllumination.BrdfCodeChangesNoBitOfALambertianScene).
TEST(ScenePlan, CompilingAnUnusedFeatureChangesNoBit) {
  const std::pair<std::set<std::string>, const char*> cases[] = {
      {{"HAS_TEXTURES", "HAS_ALPHA_MASK", "HAS_VERTEX_COLORS", "HAS_PUNCTUAL_LIGHTS", "HAS_ENVIRONMENT",
        "HAS_NORMAL_MAPS", "HAS_EMISSIVE_TEXTURES"},
       ""},
      {{"HAS_EMITTERS", "HAS_TEXTURES", "HAS_ALPHA_MASK", "HAS_VERTEX_COLORS", "HAS_ENVIRONMENT", "HAS_NORMAL_MAPS",
        "HAS_EMISSIVE_TEXTURES"},
       "lit by a point light"}};
  for (const auto& [forced, variant] : cases) {
    std::string names;
    for (const std::string& name : forced) names += name + " ";
    Scene scene = make_cornell_box();
    if (*variant) scene = cornell_under_point_light(glm::vec3(0.0f, scene.bounds_max().y - 0.1f, 0.0f));
    for (const std::string& name : forced) ASSERT_EQ(plan_scene(scene).switches.at(name), "0") << name << " is already on";
    expect_forcing_changes_no_bit(scene, forced, names);
  }
}

// Glass code compiled for a scene without glass changes no bit either, for a light off every surface. Its shadow rays
// are closest-hit queries (to find the glass they pass, kernels/glass.h) where the others are any-hit ones, and the two
// part only for a light lying in a surface's plane, where a ray ends on that plane at t = 1 and the closest hit's
// divided distance rounds to the range's end: CompilingAnUnusedFeatureChangesNoBit's point light sits in the corner
// of three walls and the light fixture's plane, and differed at 6 of 1024 direct values (by at most 6.3e-7), so glass
// is tried here, under a light in the open. (A scene without glass never compiles it: HAS_TRANSMISSION is off.)
TEST(ScenePlan, CompilingGlassCodeChangesNoBit) {
  const Scene probe = cornell_with("no emitter");
  const glm::vec3 open_air = 0.5f * (probe.bounds_min() + probe.bounds_max()) + glm::vec3(0.0f, 150.0f, 0.0f);
  expect_forcing_changes_no_bit(cornell_under_point_light(open_air), {"HAS_TRANSMISSION"}, "HAS_TRANSMISSION ");
}

// The layers' code (clearcoat, sheen, specular colour: kernels/brdf_layers.h) compiled for a scene without them changes
// no bit, on a scene whose metal block is radiance-cached and whose BRDF code runs: a surface without a coat or sheen
// takes the base BRDF's own code, so the materials of a layered scene that have no layers keep their bits too.
TEST(ScenePlan, CompilingLayersCodeChangesNoBit) {
  const Scene scene = cornell_with("glossy material");
  ASSERT_EQ(plan_scene(scene).switches.at("HAS_LAYERS"), "0");
  expect_forcing_changes_no_bit(scene, {"HAS_LAYERS"}, "HAS_LAYERS ");
}

}  // namespace
}  // namespace rcsplat
