// The glTF loader on small files written here: what it must read, and each malformed case it must reject cleanly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sequence/render_job.h"
#include "gltf_builder.h"
#include "scene/gltf_loader.h"
#include "scene/packed_scene.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// A unit quad in the xy plane, its indices with the given component type, a material and a mesh.
GltfBuilder quad_scene(int index_type) {
  GltfBuilder b;
  float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  uint32_t idx32[] = {0, 1, 2, 0, 2, 3};
  int p = b.add_accessor(b.add_view(pos, sizeof pos), 5126, 4, "VEC3");
  int t = b.add_accessor(b.add_view(uv, sizeof uv), 5126, 4, "VEC2");
  int i;
  if (index_type == 5121) {
    uint8_t idx[6];
    for (int k = 0; k < 6; ++k) idx[k] = uint8_t(idx32[k]);
    i = b.add_accessor(b.add_view(idx, sizeof idx), 5121, 6, "SCALAR");
  } else if (index_type == 5123) {
    uint16_t idx[6];
    for (int k = 0; k < 6; ++k) idx[k] = uint16_t(idx32[k]);
    i = b.add_accessor(b.add_view(idx, sizeof idx), 5123, 6, "SCALAR");
  } else {
    i = b.add_accessor(b.add_view(idx32, sizeof idx32), 5125, 6, "SCALAR");
  }
  b.doc["meshes"] = json::array({{{"name", "quad"},
                                  {"primitives", json::array({{{"attributes", {{"POSITION", p}, {"TEXCOORD_0", t}}},
                                                               {"indices", i}, {"material", 0}}})}}});
  b.doc["materials"] = json::array({{{"name", "glow"},
                                     {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"metallicFactor", 0.0}}},
                                     {"emissiveFactor", {1.0, 0.5, 0.0}},
                                     {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}});
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_lights_punctual"};
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  b.doc["scenes"] = json::array({{{"nodes", {0}}}});
  return b;
}

void expect_load_error(const std::string& path, const std::string& fragment) {
  try {
    load_gltf(path);
    ADD_FAILURE() << "loading " << path << " should have failed (" << fragment << ")";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

TEST(GltfLoader, ReadsEveryIndexWidth) {
  for (int type : {5121, 5123, 5125}) {
    std::string path = quad_scene(type).write(test::scratch_dir(), "quad" + std::to_string(type));
    Scene s = load_gltf(path);
    ASSERT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.positions[4], glm::vec3(1, 1, 0));  // second triangle's second vertex: index 2
    EXPECT_EQ(s.uvs[4], glm::vec2(1, 1));
    EXPECT_EQ(s.normals[0], glm::vec3(0, 0, 1));  // no NORMAL attribute: the geometric normal
  }
}

// The same quad as a binary .glb: a 12-byte header, then a JSON chunk and a BIN chunk, each padded to 4 bytes.
TEST(GltfLoader, ReadsBinaryGlb) {
  GltfBuilder b = quad_scene(5123);
  b.doc["buffers"] = json::array({{{"byteLength", b.bin.size()}}});
  std::string text = b.doc.dump();
  while (text.size() % 4) text += ' ';
  std::vector<uint8_t> bin = b.bin;
  while (bin.size() % 4) bin.push_back(0);
  auto u32 = [](std::string& out, uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  std::string glb;
  u32(glb, 0x46546C67);  // "glTF"
  u32(glb, 2);
  u32(glb, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(glb, uint32_t(text.size()));
  u32(glb, 0x4E4F534A);  // "JSON"
  glb += text;
  u32(glb, uint32_t(bin.size()));
  u32(glb, 0x004E4942);  // "BIN"
  glb.append(bin.begin(), bin.end());
  std::string path = test::scratch_dir() + "/quad.glb";
  test::write_file(path, glb);
  Scene s = load_gltf(path);
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.positions[4], glm::vec3(1, 1, 0));
  test::write_file(path, glb.substr(0, glb.size() - 20));  // truncated
  expect_load_error(path, path);
}

TEST(GltfLoader, ReadsMaterialsEmissionAndTransforms) {
  GltfBuilder b = quad_scene(5125);
  // Parent translates by (10, 0, 0); child rotates 90 degrees about z and scales by 2.
  b.doc["nodes"] = json::array({{{"translation", {10, 0, 0}}, {"children", {1}}},
                                {{"mesh", 0}, {"rotation", {0, 0, std::sqrt(0.5), std::sqrt(0.5)}}, {"scale", {2, 2, 2}}}});
  Scene s = load_gltf(b.write(test::scratch_dir(), "hier"));
  ASSERT_EQ(s.triangle_count(), 2u);
  glm::vec3 v1 = s.positions[1];  // local (1, 0, 0) -> scaled (2, 0, 0) -> rotated (0, 2, 0) -> translated (10, 2, 0)
  EXPECT_NEAR(v1.x, 10.0f, 1e-5f);
  EXPECT_NEAR(v1.y, 2.0f, 1e-5f);
  EXPECT_NEAR(v1.z, 0.0f, 1e-5f);
  const SceneMaterial& m = s.materials[s.triangle_material[0]];
  EXPECT_FLOAT_EQ(m.base_color.y, 0.25f);
  EXPECT_FLOAT_EQ(m.emission.x, 4.0f);
  EXPECT_FLOAT_EQ(m.emission.y, 2.0f);
}

// metallicFactor and roughnessFactor default to 1 (glTF 2.0), the dielectric's specular layer to 1
// (KHR_materials_specular); the lobe kind follows docs/NOTES.md "Material kinds". A factor outside [0, 1] is an error
// naming the material.
TEST(GltfLoader, ReadsTheBrdfParameters) {
  GltfBuilder b = quad_scene(5125);
  b.doc["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"roughnessFactor", 0.3}};
  b.doc["materials"].push_back({{"name", "matte"},
                                {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                                {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}});
  b.doc["materials"].push_back({{"name", "plaster"}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
  b.doc["meshes"].push_back(b.doc["meshes"][0]);
  b.doc["meshes"][1]["primitives"][0]["material"] = 1;
  b.doc["meshes"].push_back(b.doc["meshes"][0]);
  b.doc["meshes"][2]["primitives"][0]["material"] = 2;
  b.doc["meshes"].push_back(b.doc["meshes"][0]);
  b.doc["meshes"][3]["primitives"][0].erase("material");
  b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"mesh", 1}}, {{"mesh", 2}}, {{"mesh", 3}}});
  b.doc["scenes"] = json::array({{{"nodes", {0, 1, 2, 3}}}});
  b.doc["extensionsUsed"].push_back("KHR_materials_specular");
  Scene s = load_gltf(b.write(test::scratch_dir(), "brdf"));
  ASSERT_EQ(s.triangle_count(), 8u);
  const SceneMaterial& metal = s.materials[s.triangle_material[0]];
  EXPECT_FLOAT_EQ(metal.metallic, 1.0f);
  EXPECT_FLOAT_EQ(metal.roughness, 0.3f);
  EXPECT_FLOAT_EQ(metal.specular, 1.0f);
  const SceneMaterial& matte = s.materials[s.triangle_material[2]];
  EXPECT_FLOAT_EQ(matte.metallic, 0.0f);
  EXPECT_FLOAT_EQ(matte.roughness, 1.0f);
  EXPECT_FLOAT_EQ(matte.specular, 0.0f);
  const SceneMaterial& fallback = s.materials[s.triangle_material[6]];
  EXPECT_EQ(fallback.name, "default");
  EXPECT_FLOAT_EQ(fallback.metallic, 1.0f);
  EXPECT_FLOAT_EQ(fallback.roughness, 1.0f);

  PackedScene packed = pack_scene(s);
  EXPECT_EQ(packed.materials[s.triangle_material[0]].lobe, LOBE_GLOSSY);  // a metal at roughness 0.3
  EXPECT_EQ(packed.materials[s.triangle_material[2]].lobe, LOBE_NONE);    // no specular layer: Lambertian
  EXPECT_EQ(packed.materials[s.triangle_material[4]].lobe, LOBE_ROUGH);   // glTF's plaster: a 4% lobe at roughness 1
  EXPECT_EQ(packed.materials[s.triangle_material[6]].lobe, LOBE_ROUGH);   // a metal at roughness 1

  b.doc["materials"][1]["pbrMetallicRoughness"]["roughnessFactor"] = 1.5;
  expect_load_error(b.write(test::scratch_dir(), "brdf_bad"), "'matte': metallicFactor, roughnessFactor");
}

TEST(GltfLoader, MirroringTransformKeepsFacesFacingOut) {
  GltfBuilder b = quad_scene(5125);
  b.doc["nodes"] = json::array({{{"mesh", 0}, {"scale", {-1, 1, 1}}}});
  Scene s = load_gltf(b.write(test::scratch_dir(), "mirror"));
  glm::vec3 n = glm::cross(s.positions[1] - s.positions[0], s.positions[2] - s.positions[0]);
  EXPECT_GT(n.z, 0.0f);  // still facing +z, as the unmirrored quad
}

TEST(GltfLoader, ReadsCamerasAndLights) {
  GltfBuilder b = quad_scene(5123);
  b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}});
  b.doc["extensions"] = {{"KHR_lights_punctual",
                          {{"lights", json::array({{{"type", "point"}, {"intensity", 10.0}, {"color", {1, 0.5, 0.25}}},
                                                   {{"type", "spot"}, {"intensity", 5.0}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.4}}}},
                                                   {{"type", "directional"}, {"intensity", 2.0}}})}}}};
  b.doc["nodes"] = json::array({{{"mesh", 0}},
                                {{"camera", 0}, {"translation", {0, 0, 5}}},
                                {{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                                {{"translation", {0, 0, 4}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
                                {{"rotation", {std::sqrt(0.5), 0, 0, std::sqrt(0.5)}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}}});
  b.doc["scenes"] = json::array({{{"nodes", {0, 1, 2, 3, 4}}}});
  Scene s = load_gltf(b.write(test::scratch_dir(), "camlight"));
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].eye, glm::vec3(0, 0, 5));
  EXPECT_NEAR(s.cameras[0].target.z, 4.0f, 1e-6f);  // looks down -z
  EXPECT_FLOAT_EQ(s.cameras[0].aspect.value(), 2.0f);
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, LightType::point);
  EXPECT_EQ(s.lights[0].position, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(s.lights[0].intensity.z, 2.5f);
  EXPECT_EQ(s.lights[1].type, LightType::spot);
  EXPECT_FLOAT_EQ(s.lights[1].outer_cone, 0.4f);
  EXPECT_EQ(s.lights[2].type, LightType::directional);
  EXPECT_NEAR(s.lights[2].direction.y, 1.0f, 1e-5f);  // -z rotated 90 degrees about x points to +y
}

TEST(GltfLoader, SceneWithoutCameraOrLightGetsDefaults) {
  GltfBuilder b = quad_scene(5125);
  b.doc["materials"][0].erase("emissiveFactor");
  Scene s = load_scene(b.write(test::scratch_dir(), "bare"));
  EXPECT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.lights.size(), 1u);
}

TEST(GltfLoader, RejectsBadJson) {
  std::string path = test::scratch_dir() + "/bad.gltf";
  test::write_file(path, "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");
  expect_load_error(path, "is not valid JSON");
}

// A data URI is JSON text: past the JSON limit the file is refused before it is parsed, naming the limit.
TEST(GltfLoader, RefusesJsonBeyondItsLimitBeforeParsingIt) {
  GltfBuilder b = quad_scene(5125);
  std::string path = b.write(test::scratch_dir(), "bigjson");
  b.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(4000, 'A');
  test::write_file(path, b.doc.dump());
  SceneLimits limits;
  limits.max_json_bytes = 1000;
  try {
    load_gltf(path, limits);
    ADD_FAILURE() << "a 4 KB JSON passed a 1000-byte limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("; rcsplat reads at most 1000 bytes of glTF JSON"),
              std::string::npos) << e.what();
  }
}

TEST(GltfLoader, RejectsMissingFile) { expect_load_error(test::scratch_dir() + "/nothing.gltf", "no such file"); }

TEST(GltfLoader, RejectsMissingBuffer) {
  std::string dir = test::scratch_dir();
  std::string path = quad_scene(5125).write(dir, "nobin");
  std::filesystem::remove(dir + "/nobin.bin");
  expect_load_error(path, "buffers[0] 'nobin.bin': no such file in the scene's folder");
}

TEST(GltfLoader, RejectsTruncatedBuffer) {
  std::string dir = test::scratch_dir();
  GltfBuilder b = quad_scene(5125);
  std::string path = b.write(dir, "trunc");
  // Cut the binary file short and state the short length, so only the views' ranges reveal the damage.
  b.bin.resize(40);
  b.doc["buffers"][0]["byteLength"] = 40;
  test::write_file(dir + "/trunc.bin", std::string(b.bin.begin(), b.bin.end()));
  test::write_file(path, b.doc.dump());
  expect_load_error(path, "runs past the end of buffer");
}

TEST(GltfLoader, RejectsAccessorPastItsView) {
  GltfBuilder b = quad_scene(5125);
  b.doc["accessors"][0]["count"] = 400;
  expect_load_error(b.write(test::scratch_dir(), "overrun"), "accessors[0] (meshes[0].primitives[0].POSITION): its 400 elements run past the end of bufferViews[0]");
}

TEST(GltfLoader, RejectsOutOfRangeIndices) {
  GltfBuilder b = quad_scene(5125);
  uint32_t idx[] = {0, 1, 2, 0, 2, 7};
  b.doc["accessors"][2]["bufferView"] = b.add_view(idx, sizeof idx);
  expect_load_error(b.write(test::scratch_dir(), "badidx"), "index 7 at position 5 is out of range");
}

TEST(GltfLoader, RejectsNanPositions) {
  GltfBuilder b = quad_scene(5125);
  float pos[] = {0, 0, 0, NAN, 0, 0, 1, 1, 0, 0, 1, 0};
  b.doc["accessors"][0]["bufferView"] = b.add_view(pos, sizeof pos);
  expect_load_error(b.write(test::scratch_dir(), "nan"), "vertex 1 has a non-finite position");
}

TEST(GltfLoader, RejectsNonFiniteNormals) {
  GltfBuilder b = quad_scene(5125);
  float nrm[] = {0, 0, 1, 0, 0, 1, 0, INFINITY, 1, 0, 0, 1};
  int n = b.add_accessor(b.add_view(nrm, sizeof nrm), 5126, 4, "VEC3");
  b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = n;
  expect_load_error(b.write(test::scratch_dir(), "infnormal"), "vertex 2 has a non-finite normal");
}

// JSON has no NaN or infinity; a factor too large for single precision becomes one.
TEST(GltfLoader, RejectsFactorsAndIntensitiesBeyondSinglePrecision) {
  GltfBuilder b = quad_scene(5125);
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1e40, 0.5, 0.5, 1.0};
  expect_load_error(b.write(test::scratch_dir(), "hugecolor"), "invalid baseColorFactor");
  b = quad_scene(5125);
  b.doc["materials"][0]["emissiveFactor"] = {1.0, 1e39, 0.0};
  expect_load_error(b.write(test::scratch_dir(), "hugeemission"), "invalid emission");
  b = quad_scene(5125);
  b.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 1e40}}}}}}};
  b.doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.doc["scenes"][0]["nodes"].push_back(1);
  expect_load_error(b.write(test::scratch_dir(), "hugelight"), "invalid colour, intensity");
}

TEST(GltfLoader, RejectsAMissingTextureAndAnImageThatIsNotOne) {
  GltfBuilder b = quad_scene(5125);
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["images"] = json::array({{{"uri", "absent.png"}}});
  expect_load_error(b.write(test::scratch_dir(), "notexture"), "images[0] 'absent.png': no such file in the scene's folder");
  test::write_file(test::scratch_dir() + "/text.png", "this is not a PNG file");
  b.doc["images"] = json::array({{{"uri", "text.png"}}});
  expect_load_error(b.write(test::scratch_dir(), "textimage"), "images[0] 'text.png': not an image rcsplat reads");
}

// Found by fuzzing (tests/fuzz/corpus/found_*): a buffer URI naming a directory made tinygltf ask for 2^63 bytes; a
// scene of denormal size broke the default camera and light.
TEST(GltfLoader, RejectsABufferThatIsADirectory) {
  GltfBuilder b = quad_scene(5125);
  std::string path = b.write(test::scratch_dir(), "dirbuffer");
  b.doc["buffers"][0]["uri"] = ".";
  test::write_file(path, b.doc.dump());
  expect_load_error(path, "buffers[0] '.': not a regular file");
}

TEST(GltfLoader, RejectsAScaleBeyondWhatItRenders) {
  for (double scale : {1e-20, 1e20}) {
    GltfBuilder b = quad_scene(5125);
    b.doc["nodes"][0]["scale"] = {scale, scale, scale};
    expect_load_error(b.write(test::scratch_dir(), "scaled"), "is outside the range rcsplat renders");
  }
}

TEST(GltfLoader, SkipsNonTriangleModesAndRejectsAnEmptyResult) {
  GltfBuilder b = quad_scene(5125);
  b.doc["meshes"][0]["primitives"][0]["mode"] = 1;  // lines
  expect_load_error(b.write(test::scratch_dir(), "lines"), "no triangles");
}

TEST(GltfLoader, RejectsNodeCycles) {
  GltfBuilder b = quad_scene(5125);
  b.doc["nodes"] = json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}});
  expect_load_error(b.write(test::scratch_dir(), "cycle"), "cycle");
}

// The command as a user runs it: a malformed scene gives an error and leaves no output file behind.
TEST(GltfLoader, RenderOfMalformedSceneWritesNothing) {
  std::string dir = test::scratch_dir();
  std::string bad = dir + "/broken.gltf";
  test::write_file(bad, "not json at all");
  const test::CommandRun run = test::run_rcsplat(dir, {"render", bad, "-o", "out.exr", "-o", "out.png"});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find("broken.gltf"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.png"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
}

TEST(GltfLoader, LoadsEverySharedScene) {
  std::filesystem::path root = std::filesystem::path(RCSPLAT_SOURCE_DIR) / "../shared/scenes";
  if (!std::filesystem::exists(root)) GTEST_SKIP() << root << " is absent";
  size_t loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".gltf") continue;
    SCOPED_TRACE(entry.path().string());
    Scene s = load_gltf(entry.path().string());
    EXPECT_GT(s.triangle_count(), 0u);
    EXPECT_FALSE(s.cameras.empty());
    ++loaded;
  }
  EXPECT_GE(loaded, 7u);
}

}  // namespace
}  // namespace rcsplat
