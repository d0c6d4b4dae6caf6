// glTF 2.0 conformance for a still image, one small file per feature, each checked against what the feature must
// produce: a sparse accessor's values, a morphed vertex, a skinned vertex, normalised integer texture coordinates, a
// transformed UV, a vertex colour's albedo; defaults that follow the camera the user chose; camera errors that list
// the file's cameras; features not simulated named once.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <webp/encode.h>

#include <cmath>

#include "sequence/render_job.h"
#include "image/image_io.h"
#include "gltf_builder.h"
#include "test_support.h"
#include "render/camera.h"
#include "bvh/bvh8.h"
#include "cl/device_scene.h"
#include "passes/ray_cast_pass.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/scene_plan.h"
#include "scene/tangents.h"
#include "util/error.h"

namespace rcsplat {
namespace {

using test::GltfBuilder;
using test::json;

constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123;

// A unit quad in the xy plane facing +z (4 vertices, 2 triangles); returns the position accessor.
int add_quad(GltfBuilder& b, json attributes = json::object(), int material = -1) {
  float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  uint16_t idx[] = {0, 1, 2, 0, 2, 3};
  int p = b.add_accessor(b.add_view(pos, sizeof pos), kFloat, 4, "VEC3");
  int i = b.add_accessor(b.add_view(idx, sizeof idx), kUnsignedShort, 6, "SCALAR");
  attributes["POSITION"] = p;
  json primitive = {{"attributes", attributes}, {"indices", i}};
  if (material >= 0) primitive["material"] = material;
  b.doc["meshes"].push_back({{"primitives", json::array({primitive})}});
  return p;
}

Scene load(GltfBuilder& b, const std::string& name) { return load_gltf(b.write(test::scratch_dir(), name)); }

void expect_vec3(const glm::vec3& a, const glm::vec3& b, float tolerance, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << what << " component " << k;
}

TEST(GltfConformance, SparseAccessorSubstitutesItsValues) {
  GltfBuilder b;
  add_quad(b);
  // Vertices 1 and 3 of the position accessor moved by a sparse substitution.
  uint8_t which[] = {1, 3};
  float moved[] = {2, 0, 0, 0, 3, 0};
  b.doc["accessors"][0]["sparse"] = {{"count", 2},
                                     {"indices", {{"bufferView", b.add_view(which, sizeof which)}, {"componentType", kUnsignedByte}}},
                                     {"values", {{"bufferView", b.add_view(moved, sizeof moved)}}}};
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  Scene s = load(b, "sparse");
  ASSERT_EQ(s.triangle_count(), 2u);
  expect_vec3(s.positions[1], {2, 0, 0}, 0.0f, "vertex 1");  // triangle (0, 1, 2)
  expect_vec3(s.positions[5], {0, 3, 0}, 0.0f, "vertex 3");  // triangle (0, 2, 3)
  expect_vec3(s.positions[2], {1, 1, 0}, 0.0f, "vertex 2 (not substituted)");

  // A substitution naming an element past the accessor is refused by name.
  which[1] = 9;
  GltfBuilder bad = b;
  bad.bin.clear();
  bad.doc = json{{"asset", {{"version", "2.0"}}}};
  add_quad(bad);
  bad.doc["accessors"][0]["sparse"] = {{"count", 2},
                                       {"indices", {{"bufferView", bad.add_view(which, sizeof which)}, {"componentType", kUnsignedByte}}},
                                       {"values", {{"bufferView", bad.add_view(moved, sizeof moved)}}}};
  bad.doc["nodes"] = json::array({{{"mesh", 0}}});
  EXPECT_THROW(load(bad, "sparse_bad"), Error);
}

TEST(GltfConformance, MorphTargetsAtTheDefaultWeights) {
  GltfBuilder b;
  add_quad(b);
  float delta[] = {0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0};  // vertex 1 moves along +z
  int target = b.add_accessor(b.add_view(delta, sizeof delta), kFloat, 4, "VEC3");
  b.doc["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", target}}});
  b.doc["meshes"][0]["weights"] = {0.5};
  b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"mesh", 0}, {"weights", {0.25}}, {"translation", {5, 0, 0}}}});
  Scene s = load(b, "morph");
  ASSERT_EQ(s.triangle_count(), 4u);
  expect_vec3(s.positions[1], {1, 0, 1.0f}, 1e-6f, "mesh weight 0.5");
  expect_vec3(s.positions[7], {6, 0, 0.5f}, 1e-6f, "node weight 0.25 overrides the mesh's");
}

TEST(GltfConformance, SkinnedMeshIsPosedByItsJoints) {
  GltfBuilder b;
  uint8_t joints[] = {0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
  float weights[] = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0};
  add_quad(b, {{"JOINTS_0", b.add_accessor(b.add_view(joints, sizeof joints), kUnsignedByte, 4, "VEC4")},
               {"WEIGHTS_0", b.add_accessor(b.add_view(weights, sizeof weights), kFloat, 4, "VEC4")}});
  // Joint 1 (node 2) sits at y = 2 with an inverse bind of identity; joint 0 (node 1) at the origin. The mesh node's
  // own translation must be ignored, as the specification says.
  b.doc["skins"] = json::array({{{"joints", {1, 2}}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}, {"skin", 0}, {"translation", {100, 0, 0}}},
                                {{"children", {2}}},
                                {{"translation", {0, 2, 0}}}});
  b.doc["scenes"] = json::array({{{"nodes", {0, 1}}}});
  Scene s = load(b, "skin");
  ASSERT_EQ(s.triangle_count(), 2u);
  expect_vec3(s.positions[0], {0, 0, 0}, 1e-6f, "vertex 0 on joint 0");
  expect_vec3(s.positions[1], {1, 2, 0}, 1e-6f, "vertex 1 on joint 1");
  expect_vec3(s.positions[2], {1, 2, 0}, 1e-6f, "vertex 2 half on each: (1,1,0) + 0.5 * (0,2,0)");
}

TEST(GltfConformance, NormalizedIntegerTexcoordsAndTextureTransform) {
  GltfBuilder b;
  uint16_t uv[] = {0, 0, 65535, 0, 65535, 65535, 0, 32768};
  int t = b.add_accessor(b.add_view(uv, sizeof uv), kUnsignedShort, 4, "VEC2");
  b.doc["accessors"][size_t(t)]["normalized"] = true;
  add_quad(b, {{"TEXCOORD_0", t}}, 0);
  b.doc["materials"] = json::array(
      {{{"pbrMetallicRoughness",
         {{"metallicFactor", 0.0},
          {"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform",
                                                               {{"offset", {0.5, 0.25}}, {"scale", {2.0, 3.0}},
                                                                {"rotation", 1.5707963267948966}}}}}}}}}}});
  // A 1x1 texture: only the UVs matter here.
  write_png_display(test::scratch_dir() + "/white.png", 1, 1, {1, 1, 1});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["images"] = json::array({{{"uri", "white.png"}}});
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  Scene s = load(b, "uv");
  // uv' = T * R(pi/2) * S * uv with R's columns (c, s) and (-s, c): (u, v) -> (0.5 - 3 v, 0.25 + 2 u).
  auto expected = [](float u, float v) { return glm::vec2(0.5f - 3.0f * v, 0.25f + 2.0f * u); };
  glm::vec2 want[] = {expected(0, 0), expected(1, 0), expected(1, 1), expected(0, 0), expected(1, 1),
                      expected(0, 32768.0f / 65535.0f)};
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(s.uvs[size_t(k)].x, want[k].x, 1e-5f) << "corner " << k;
    EXPECT_NEAR(s.uvs[size_t(k)].y, want[k].y, 1e-5f) << "corner " << k;
  }
  EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

// A 2 x 1 texture, black then white, on a unit quad filling an orthographic view: with the sampler's NEAREST filter a
// pixel at u = 0.28 is the black texel exactly, with LINEAR a sixteenth of the white one.
float albedo_at_quarter(bool nearest) {
  GltfBuilder b;
  std::string dir = test::scratch_dir();
  write_png_display(dir + "/two.png", 2, 1, {0, 0, 0, 1, 1, 1});
  float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  int t = b.add_accessor(b.add_view(uv, sizeof uv), kFloat, 4, "VEC2");
  add_quad(b, {{"TEXCOORD_0", t}}, 0);
  b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["samplers"] = json::array({{{"magFilter", nearest ? 9728 : 9729}, {"wrapS", 33071}, {"wrapT", 33071}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  b.doc["images"] = json::array({{{"uri", "two.png"}}});
  b.doc["cameras"] = json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 0.5}, {"ymag", 0.5}, {"znear", 0.1}, {"zfar", 10.0}}}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"camera", 0}, {"translation", {0.5, 0.5, 3}}}});
  Scene scene = load_gltf(b.write(dir, nearest ? "nearest" : "linear"));
  add_view_defaults(scene, 0, {});
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 16;
  settings.gi = GiMethod::none;
  RenderedImage img = render(test::gpu(), scene, settings);
  return img.albedo[3 * size_t(8 * 16 + 4)];  // pixel (4, 8): u = 4.5 / 16
}

TEST(GltfConformance, SamplerFilterNearestOrLinear) {
  EXPECT_EQ(albedo_at_quarter(true), 0.0f);
  EXPECT_NEAR(albedo_at_quarter(false), 0.0625f, 1e-4f);
}

// Alpha mode MASK: a unit quad at z = 0 whose texture is transparent on its left half (alpha 0) and opaque on its
// right, in front of an opaque wall at z = -1, lit by a point light in front. Through the hole, the primary ray sees
// the wall, the wall's shadow ray reaches the light, and a cast ray (as hemisphere rays trace) hits the wall.
TEST(GltfConformance, AlphaMaskMakesHolesForEveryRay) {
  std::string dir = test::scratch_dir();
  {
    unsigned char texels[] = {255, 255, 255, 0, 255, 255, 255, 255};
    auto out = OIIO::ImageOutput::create(dir + "/half.png");
    ASSERT_TRUE(out && out->open(dir + "/half.png", OIIO::ImageSpec(2, 1, 4, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, texels));
    out->close();
  }
  GltfBuilder b;
  float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  int t = b.add_accessor(b.add_view(uv, sizeof uv), kFloat, 4, "VEC2");
  add_quad(b, {{"TEXCOORD_0", t}}, 0);  // mesh 0: the masked quad
  add_quad(b, json::object(), 1);        // mesh 1: the wall
  b.doc["materials"] = json::array(
      {{{"alphaMode", "MASK"}, {"alphaCutoff", 0.5}, {"doubleSided", true},
        {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"baseColorTexture", {{"index", 0}}}}}},
       {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}});
  b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33071}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  b.doc["images"] = json::array({{{"uri", "half.png"}}});
  b.doc["cameras"] = json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 0.5}, {"ymag", 0.5}, {"znear", 0.1}, {"zfar", 10.0}}}}});
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", json::array({{{"type", "point"}, {"intensity", 10.0}}})}}}};
  b.doc["nodes"] = json::array({{{"mesh", 0}},
                                {{"mesh", 1}, {"translation", {-1, -1, -1}}, {"scale", {3, 3, 1}}},
                                {{"camera", 0}, {"translation", {0.5, 0.5, 3}}},
                                {{"translation", {0.5, 0.5, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}});
  Scene scene = load_gltf(b.write(dir, "masked"));
  EXPECT_TRUE(scene.unsupported.empty()) << scene.unsupported.front();
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 16;
  settings.gi = GiMethod::none;
  RenderedImage img = render(test::gpu(), scene, settings);
  size_t hole = size_t(8 * 16 + 4), solid = size_t(8 * 16 + 11);  // u = 0.28 and u = 0.72
  EXPECT_NEAR(img.position[3 * hole + 2], -1.0f, 1e-5f) << "the primary ray passes the hole";
  EXPECT_NEAR(img.position[3 * solid + 2], 0.0f, 1e-5f) << "the opaque half is solid";
  EXPECT_GT(img.direct[3 * hole], 0.0f) << "the wall behind the hole sees the light through it";

  Bvh8 bvh = build_bvh8(scene.positions);
  DeviceScene device(test::gpu(), scene, bvh);
  RayCastPass caster(test::gpu(), device);
  caster.set_rays({RayDesc{{0.25f, 0.5f, 1.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 10.0f},
                   RayDesc{{0.75f, 0.5f, 1.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 10.0f},
                   RayDesc{{0.25f, 0.5f, 1.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 1.5f}});
  caster.cast_closest();
  std::vector<HitDesc> hits = caster.closest_hits();
  EXPECT_GE(hits[0].prim, 2) << "through the hole: the wall (triangles 2 and 3)";
  EXPECT_NEAR(hits[0].t, 2.0f, 1e-5f);
  EXPECT_LT(hits[1].prim, 2) << "the opaque half: the quad (triangles 0 and 1)";
  caster.cast_occlusion();
  EXPECT_EQ(caster.occlusion()[2], 0) << "a shadow ray through the hole that stops short of the wall is not occluded";
}

TEST(GltfConformance, VertexColorMultipliesTheBaseColor) {
  GltfBuilder b;
  uint8_t rgba[] = {255, 128, 0, 255, 255, 128, 0, 255, 255, 128, 0, 255, 255, 128, 0, 255};
  int c = b.add_accessor(b.add_view(rgba, sizeof rgba), kUnsignedByte, 4, "VEC4");
  b.doc["accessors"][size_t(c)]["normalized"] = true;
  add_quad(b, {{"COLOR_0", c}}, 0);
  b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}}}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  Scene scene = load(b, "colors");
  ASSERT_TRUE(scene.has_vertex_colors());
  add_view_defaults(scene, 0, {});
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 16;
  settings.gi = GiMethod::none;
  RenderedImage img = render(test::gpu(), scene, settings);
  size_t centre = size_t(8 * 16 + 8);
  ASSERT_GE(img.triangle[centre], 0);
  // Linear vertex colour (1, 128/255, 0), stored with 10 bits a channel, times the base colour.
  EXPECT_NEAR(img.albedo[3 * centre], 0.8f, 1e-6f);
  EXPECT_NEAR(img.albedo[3 * centre + 1], 0.8f * 128.0f / 255.0f, 0.8f / 1023.0f);
  EXPECT_NEAR(img.albedo[3 * centre + 2], 0.0f, 1e-7f);
}

// A quad seen from behind through --eye: the default light must sit above the camera actually used, or the side the
// camera sees is unlit; and no warning may claim a default camera the user replaced.
TEST(GltfConformance, DefaultLightFollowsTheCameraTheUserGave) {
  GltfBuilder b;
  add_quad(b);
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  std::string path = b.write(test::scratch_dir(), "bare_quad");
  CameraOverrides view;
  view.eye = glm::vec3(0.5f, 0.5f, -3.0f);
  view.target = glm::vec3(0.5f, 0.5f, 0.0f);
  testing::internal::CaptureStderr();
  Scene scene = load_scene(path, 0, view);
  std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(warnings.find("default camera"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("default point light"), std::string::npos) << warnings;
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_LT(scene.lights[0].position.z, 0.0f) << "the light should be on the side of the camera at z = -3";

  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 16;
  settings.gi = GiMethod::none;
  settings.camera_overrides = view;
  RenderedImage img = render(test::gpu(), scene, settings);
  size_t centre = size_t(8 * 16 + 8);
  ASSERT_GE(img.triangle[centre], 0);
  EXPECT_GT(img.direct[3 * centre], 0.0f) << "the far side of the quad, seen through --eye, is lit";
}

TEST(GltfConformance, CameraErrorsListTheFilesCameras) {
  GltfBuilder b;
  add_quad(b);
  b.doc["cameras"] = json::array({{{"name", "Front"}, {"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}},
                                  {{"name", "Plan"}, {"type", "orthographic"},
                                   {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 10.0}}}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"camera", 0}, {"translation", {0.5, 0.5, 3}}},
                                {{"camera", 1}, {"translation", {0.5, 0.5, 3}}}});
  Scene scene = load(b, "cameras");
  ASSERT_EQ(scene.cameras.size(), 2u);
  for (int index : {2, 5}) {
    try {
      choose_camera(scene, index, {});
      ADD_FAILURE() << "camera " << index << " was accepted";
    } catch (const Error& e) {
      std::string message = e.what();
      EXPECT_NE(message.find("0 'Front' (perspective)"), std::string::npos) << message;
      EXPECT_NE(message.find("1 'Plan' (orthographic)"), std::string::npos) << message;
    }
  }
  EXPECT_NO_THROW(choose_camera(scene, 0, {}));
  EXPECT_TRUE(choose_camera(scene, 1, {}).orthographic);
  EXPECT_TRUE(scene.unsupported.empty()) << scene.unsupported.front();
}

// An orthographic camera's rays start on the plane through its eye, one per pixel centre, and run along its axis:
// on the plane z = 0 seen from z = 3, pixel (x, y) sees (eye.x + (2 (x + 0.5) / w - 1) xmag, eye.y + ..., 0).
TEST(GltfConformance, OrthographicCameraRaysAreParallel) {
  GltfBuilder b;
  add_quad(b);
  b.doc["cameras"] = json::array({{{"name", "Plan"}, {"type", "orthographic"},
                                   {"orthographic", {{"xmag", 0.4}, {"ymag", 0.2}, {"znear", 0.1}, {"zfar", 10.0}}}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"camera", 0}, {"translation", {0.5, 0.5, 3}}}});
  Scene scene = load(b, "orthographic");
  add_view_defaults(scene, 0, {});
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = 32;  // the height follows xmag / ymag: 16
  settings.gi = GiMethod::none;
  RenderedImage img = render(test::gpu(), scene, settings);
  ASSERT_EQ(img.height, 16);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      size_t i = size_t(y * img.width + x);
      ASSERT_GE(img.triangle[i], 0) << x << "," << y;
      float px = 0.5f + (2.0f * (float(x) + 0.5f) / float(img.width) - 1.0f) * 0.4f;
      float py = 0.5f + (1.0f - 2.0f * (float(y) + 0.5f) / float(img.height)) * 0.2f;
      ASSERT_NEAR(img.position[3 * i], px, 1e-6f) << x << "," << y;
      ASSERT_NEAR(img.position[3 * i + 1], py, 1e-6f) << x << "," << y;
      ASSERT_NEAR(img.depth[i], 3.0f, 1e-5f);
    }
  CameraOverrides fov;
  fov.fov_degrees = 30.0f;
  EXPECT_THROW(choose_camera(scene, 0, fov), Error);
}

TEST(GltfConformance, FeaturesNotSimulatedAreNamedOnce) {
  const std::string dir = test::scratch_dir();
  {
    unsigned char texels[] = {128, 128, 255, 255};
    auto out = OIIO::ImageOutput::create(dir + "/flat.png");
    ASSERT_TRUE(out && out->open(dir + "/flat.png", OIIO::ImageSpec(1, 1, 4, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, texels));
    out->close();
  }
  GltfBuilder b;
  float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const int t = b.add_accessor(b.add_view(uv, sizeof uv), kFloat, 4, "VEC2");
  add_quad(b, {{"TEXCOORD_0", t}}, 0);
  b.doc["meshes"].push_back(b.doc["meshes"][0]);
  b.doc["meshes"][1]["primitives"][0]["material"] = 1;
  json coloured_specular = {{"KHR_materials_specular", {{"specularColorFactor", {1.0, 0.5, 0.5}}}}};
  b.doc["materials"] = json::array(
      {{{"pbrMetallicRoughness", {{"metallicFactor", 1.0}}}, {"alphaMode", "BLEND"}, {"extensions", coloured_specular},
        {"normalTexture", {{"index", 0}}}, {"occlusionTexture", {{"index", 0}}}},
       {{"pbrMetallicRoughness", {{"metallicFactor", 0.5}}}, {"alphaMode", "BLEND"}, {"extensions", coloured_specular},
        {"normalTexture", {{"index", 0}}}}});
  b.doc["images"] = json::array({{{"uri", "flat.png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["extensionsUsed"] = {"KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_specular"};
  b.doc["animations"] = json::array({{{"channels", json::array()}, {"samplers", json::array()}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}, {{"mesh", 1}}});
  Scene scene = load_gltf(b.write(dir, "unsupported"));
  std::vector<std::string> keys = {"KHR_materials_iridescence", "KHR_materials_anisotropy", "animation",
                                   "occlusionTexture"};
  for (const std::string& key : keys) {
    size_t found = 0;
    for (const std::string& line : scene.unsupported) found += line.find(key) != std::string::npos;
    EXPECT_EQ(found, 1u) << key;
  }
  EXPECT_EQ(scene.unsupported.size(), keys.size());
  EXPECT_EQ(scene.materials[0].normal_texture, 0) << "normal maps are simulated";
  EXPECT_TRUE(scene.materials[0].alpha_blend) << "alpha mode BLEND is simulated";
}

// EXT_texture_webp: a texture whose image is WebP (lossless here, so its texels come back exactly) is read through
// libwebp; a damaged one is refused naming the image.
TEST(GltfConformance, WebPTexturesAreRead) {
  const std::string dir = test::scratch_dir();
  const uint8_t rgba[8] = {10, 200, 30, 255, 250, 128, 0, 90};
  uint8_t* encoded = nullptr;
  const size_t bytes = WebPEncodeLosslessRGBA(rgba, 2, 1, 8, &encoded);
  ASSERT_GT(bytes, 0u);
  test::write_file(dir + "/two.webp", std::string(reinterpret_cast<const char*>(encoded), bytes));
  test::write_file(dir + "/broken.webp", std::string(reinterpret_cast<const char*>(encoded), bytes / 2));
  WebPFree(encoded);
  auto scene_with = [&](const std::string& image) {
    GltfBuilder b;
    float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
    add_quad(b, {{"TEXCOORD_0", b.add_accessor(b.add_view(uv, sizeof uv), kFloat, 4, "VEC2")}}, 0);
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.doc["images"] = json::array({{{"uri", image}}});
    b.doc["textures"] = json::array({{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}});
    b.doc["extensionsUsed"] = {"EXT_texture_webp"};
    b.doc["extensionsRequired"] = {"EXT_texture_webp"};
    b.doc["nodes"] = json::array({{{"mesh", 0}}});
    return b.write(dir, "webp");
  };
  const Scene scene = load_gltf(scene_with("two.webp"));
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].width, 2);
  EXPECT_EQ(scene.textures[0].height, 1);
  EXPECT_EQ(scene.textures[0].rgba, std::vector<uint8_t>(rgba, rgba + 8));
  EXPECT_EQ(scene.materials[0].base_color_texture, 0);
  EXPECT_TRUE(scene.unsupported.empty());
  try {
    load_gltf(scene_with("broken.webp"));
    ADD_FAILURE() << "a truncated WebP was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.webp"), std::string::npos) << e.what();
  }
}

// A file of one quad whose one material (dielectric, this roughness) carries these extensions; its path.
std::string one_material_quad(const std::string& dir, const std::string& name, const std::string& material,
                              double roughness, const json& extensions) {
  GltfBuilder b;
  add_quad(b, json::object(), 0);
  b.doc["materials"] = json::array({{{"name", material},
                                     {"pbrMetallicRoughness", {{"roughnessFactor", roughness}, {"metallicFactor", 0.0}}},
                                     {"extensions", extensions}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  return b.write(dir, name);
}

// Each (material extensions, word) loads as a file the loader refuses, its message naming the material and the word.
template <size_t N, typename WriteScene>
void expect_each_refused(const std::pair<json, const char*> (&refused)[N], WriteScene write, const std::string& material) {
  for (const auto& [extensions, word] : refused) {
    try {
      load_gltf(write(extensions));
      ADD_FAILURE() << extensions.dump() << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(material), std::string::npos) << what;
      EXPECT_NE(what.find(word), std::string::npos) << what;
    }
  }
}

// Glass: KHR_materials_transmission, _ior and _volume read as their texts define them (defaults where a field is
// left out), the scene plan compiling glass code for them and no other, and each malformed value refused by name.
TEST(GltfConformance, GlassExtensionsAreReadAndChecked) {
  const std::string dir = test::scratch_dir();
  auto scene_with = [&](const json& extensions, const std::string& name) {
    return one_material_quad(dir, name, "pane", 0.0, extensions);
  };
  const Scene glass = load_gltf(scene_with(
      {{"KHR_materials_transmission", {{"transmissionFactor", 0.8}}},
       {"KHR_materials_ior", {{"ior", 1.33}}},
       {"KHR_materials_volume",
        {{"thicknessFactor", 0.2}, {"attenuationDistance", 2.0}, {"attenuationColor", {0.5, 0.25, 1.0}}}}},
      "glass"));
  const SceneMaterial& m = glass.materials[0];
  EXPECT_FLOAT_EQ(m.transmission, 0.8f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.thickness, 0.2f);
  EXPECT_FLOAT_EQ(m.attenuation_distance, 2.0f);
  EXPECT_EQ(m.attenuation_color, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_TRUE(glass.unsupported.empty()) << glass.unsupported.front();
  const ScenePlan plan = plan_scene(glass);
  EXPECT_EQ(plan.switches.at("HAS_TRANSMISSION"), "1");
  EXPECT_EQ(plan.glass_materials, 1u);
  EXPECT_FALSE(plan.materials[0].thin_walled);
  // Defaults: the volume's attenuation infinitely far (clear), ior 1.5, thin-walled without a volume.
  const Scene thin = load_gltf(scene_with({{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}, "thin"));
  EXPECT_FLOAT_EQ(thin.materials[0].ior, 1.5f);
  EXPECT_EQ(thin.materials[0].thickness, 0.0f);
  EXPECT_TRUE(std::isinf(thin.materials[0].attenuation_distance));
  EXPECT_TRUE(plan_scene(thin).materials[0].thin_walled);
  const std::pair<json, const char*> refused[] = {
      {{{"KHR_materials_ior", {{"ior", 0.9}}}}, "ior"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}, "transmissionFactor"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", "all"}}}}, "transmissionFactor"},
      {{{"KHR_materials_volume", {{"attenuationDistance", -1.0}}}}, "attenuationDistance"},
      {{{"KHR_materials_volume", {{"attenuationColor", {0.5, 2.0, 0.5}}}}}, "attenuationColor"},
      {{{"KHR_materials_volume", {{"thicknessFactor", -0.1}}}}, "thicknessFactor"}};
  expect_each_refused(refused, [&](const json& extensions) { return scene_with(extensions, "refused"); },
                      "materials[0] 'pane'");
}

// Layers: KHR_materials_clearcoat, KHR_materials_sheen and KHR_materials_specular's colour read as their texts define
// them (defaults where a field is left out), the scene plan compiling the layers' code for them, and each malformed
// value refused by name. A layer on glass is named: glass reflects as uncoated glass.
TEST(GltfConformance, LayerExtensionsAreReadAndChecked) {
  const std::string dir = test::scratch_dir();
  auto scene_with = [&](const json& extensions, const std::string& name, double transmission = 0.0) {
    json material_extensions = extensions;
    if (transmission > 0.0) material_extensions["KHR_materials_transmission"] = {{"transmissionFactor", transmission}};
    return one_material_quad(dir, name, "paint", 0.5, material_extensions);
  };
  const Scene layered = load_gltf(scene_with(
      {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.7}, {"clearcoatRoughnessFactor", 0.1}}},
       {"KHR_materials_sheen", {{"sheenColorFactor", {0.5, 0.25, 1.0}}, {"sheenRoughnessFactor", 0.4}}},
       {"KHR_materials_specular", {{"specularColorFactor", {2.0, 1.0, 0.5}}}}},
      "layered"));
  const SceneMaterial& m = layered.materials[0];
  EXPECT_FLOAT_EQ(m.clearcoat, 0.7f);
  EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.1f);
  EXPECT_EQ(m.sheen_color, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(m.sheen_roughness, 0.4f);
  EXPECT_EQ(m.specular_color, glm::vec3(2.0f, 1.0f, 0.5f));
  EXPECT_TRUE(layered.unsupported.empty()) << layered.unsupported.front();
  const ScenePlan plan = plan_scene(layered);
  EXPECT_EQ(plan.switches.at("HAS_LAYERS"), "1");
  EXPECT_EQ(plan.layered_materials, 1u);
  EXPECT_TRUE(plan.materials[0].clearcoat && plan.materials[0].sheen && plan.materials[0].specular_colour);
  EXPECT_EQ(plan.materials[0].lobe, LOBE_GLOSSY) << "a coat of roughness 0.1 is sampled per pixel";
  // Defaults: clearcoatFactor 0 (no coat), sheenColorFactor 0 (no sheen): nothing to compile.
  const Scene bare = load_gltf(scene_with({{"KHR_materials_clearcoat", json::object()}, {"KHR_materials_sheen", json::object()}}, "bare"));
  EXPECT_EQ(bare.materials[0].clearcoat, 0.0f);
  EXPECT_EQ(bare.materials[0].sheen_color, glm::vec3(0.0f));
  EXPECT_EQ(plan_scene(bare).switches.at("HAS_LAYERS"), "0");
  const Scene coated_glass =
      load_gltf(scene_with({{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}, "coated_glass", 1.0));
  size_t named = 0;
  for (const std::string& line : coated_glass.unsupported) named += line.find("on glass") != std::string::npos;
  EXPECT_EQ(named, 1u);
  EXPECT_EQ(plan_scene(coated_glass).switches.at("HAS_LAYERS"), "0");
  const std::pair<json, const char*> refused[] = {
      {{{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}}}, "clearcoatFactor"},
      {{{"KHR_materials_clearcoat", {{"clearcoatRoughnessFactor", -0.1}}}}, "clearcoatRoughnessFactor"},
      {{{"KHR_materials_clearcoat", {{"clearcoatFactor", "shiny"}}}}, "clearcoatFactor"},
      {{{"KHR_materials_sheen", {{"sheenColorFactor", {2.0, 0.0, 0.0}}}}}, "sheenColorFactor"},
      {{{"KHR_materials_sheen", {{"sheenColorFactor", {0.5, 0.5}}}}}, "sheenColorFactor"},
      {{{"KHR_materials_sheen", {{"sheenRoughnessFactor", 2.0}}}}, "sheenRoughnessFactor"},
      {{{"KHR_materials_specular", {{"specularColorFactor", {-1.0, 0.0, 0.0}}}}}, "specularColorFactor"}};
  expect_each_refused(refused, [&](const json& extensions) { return scene_with(extensions, "refused"); },
                      "materials[0] 'paint'");
}

// Texture filtering by ray footprint: a floor of a one-texel checker (black and white, linear mean 1/2) running away
// from the camera. Where a pixel's cone covers several texels its albedo is the checker's mean (the mip chain is
// averaged in linear light), whatever texel its centre lands on; sampled at full resolution (the sampler's minFilter
// LINEAR, no mipmaps) the same pixels alias between black and white.
TEST(GltfConformance, DistantTexturesAreFilteredByTheRaysFootprint) {
  Scene s;
  s.source = "checker floor";
  SceneTexture checker;
  checker.width = checker.height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const uint8_t v = (x + y) % 2 ? 255 : 0;
      checker.rgba.insert(checker.rgba.end(), {v, v, v, 255});
    }
  s.textures.push_back(checker);
  SceneMaterial floor{"floor", glm::vec4(1.0f), 0, glm::vec3(0.0f), false};
  s.materials.push_back(floor);
  s.add_quad({-50, 0, 10}, {50, 0, 10}, {50, 0, -400}, {-50, 0, -400}, 0);
  for (size_t k = 0; k < s.positions.size(); ++k) s.uvs[k] = glm::vec2(s.positions[k].x, s.positions[k].z) / 8.0f;
  SceneCamera cam;
  cam.eye = {0, 2, 0};
  cam.target = {0, 0, -20};
  cam.yfov = 1.0f;
  s.cameras.push_back(cam);
  SceneLight light;
  light.type = LightType::directional;
  light.direction = {0, -1, 0};
  s.lights.push_back(light);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.gi = GiMethod::none;
  settings.width = settings.height = 64;
  auto far_spread = [&](bool mipmaps, size_t* pixels) {
    Scene scene = s;
    scene.textures[0].mipmaps = mipmaps;
    const RenderedImage img = render(test::gpu(), scene, settings);
    double worst = 0.0, mean_deviation = 0.0;
    *pixels = 0;
    for (size_t i = 0; i < img.triangle.size(); ++i) {
      if (img.triangle[i] < 0 || img.depth[i] < 20.0f) continue;  // far: a pixel covers 3 texels or more
      const double deviation = std::fabs(double(img.albedo[3 * i + 1]) - 0.5);
      worst = std::max(worst, deviation);
      mean_deviation += deviation;
      ++*pixels;
    }
    std::printf("mipmaps %d: %zu far pixels, albedo off the checker's mean by %.3f at most, %.3f on average\n",
                int(mipmaps), *pixels, worst, mean_deviation / double(std::max<size_t>(*pixels, 1)));
    return std::pair{worst, mean_deviation / double(std::max<size_t>(*pixels, 1))};
  };
  size_t pixels = 0;
  const auto filtered = far_spread(true, &pixels);
  ASSERT_GT(pixels, 250u);
  // The mip level's own rounding (an 8-bit sRGB code for 1/2) and the trilinear blend's: a few thousandths.
  EXPECT_LT(filtered.first, 0.02);
  const auto aliased = far_spread(false, &pixels);
  EXPECT_GT(aliased.first, 0.2) << "without mipmaps the far floor must alias (else the test proves nothing)";
}

// Tangents where the file has none (after MikkTSpace): the angle-weighted sum of the texture-coordinate gradients of
// the corners sharing a vertex and a handedness, orthogonal to the normal, with w saying which way the image's up
// runs. Checked against gradients worked out by hand: a quad whose u
// runs along a rotated axis, and the same quad with its image mirrored (w flips).
TEST(GltfConformance, GeneratedTangentsFollowTheTextureCoordinates) {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const double angle = 0.3;
  const glm::dvec2 u_axis(std::cos(angle), std::sin(angle));  // u grows along this world direction
  for (double mirror : {1.0, -1.0}) {
    std::vector<float> uvs;
    for (const glm::vec3& p : positions) {
      glm::dvec2 q(p.x, p.y);
      uvs.push_back(float(glm::dot(q, u_axis)));
      // v grows along mirror times the perpendicular (and glTF's v grows down the image).
      uvs.push_back(float(mirror * glm::dot(q, glm::dvec2(-u_axis.y, u_axis.x))));
    }
    const std::vector<glm::vec4> t = generate_tangents(indices, positions, {}, uvs);
    ASSERT_EQ(t.size(), 6u);
    for (const glm::vec4& v : t) {
      EXPECT_NEAR(v.x, u_axis.x, 1e-6);
      EXPECT_NEAR(v.y, u_axis.y, 1e-6);
      EXPECT_NEAR(v.z, 0.0, 1e-6);
      // Image up is -dP/dv = -mirror * perpendicular; cross(n, t) = +perpendicular.
      EXPECT_EQ(v.w, float(-mirror));
    }
  }
  // A quad whose two triangles are mirrored in texture space (the second's v runs the other way): each corner keeps
  // its own triangle's handedness, and the shared corners do not average the two frames away.
  {
    const std::vector<float> folded = {0, 0, 1, 0, 1, 1, 0, 1};
    const std::vector<glm::vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, -1, 0}};
    const std::vector<glm::vec4> t = generate_tangents({0, 1, 2, 0, 3, 1}, quad, {}, folded);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(t[size_t(k)].w, -1.0f) << "corner " << k;
    for (int k = 3; k < 6; ++k) EXPECT_EQ(t[size_t(k)].w, 1.0f) << "corner " << k;
    for (const glm::vec4& v : t) EXPECT_NEAR(v.x, 1.0, 1e-6);
  }
  // A triangle whose texture coordinates are all equal has no gradient: w = 0, no normal map there.
  const std::vector<glm::vec4> flat = generate_tangents({0, 1, 2}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, std::vector<float>(6, 0.5f));
  for (const glm::vec4& v : flat) EXPECT_EQ(v.w, 0.0f);
}

// A normal-mapped quad: tangents come from TANGENT when the file has it (turned by the node's transform; a mirroring
// one flips w) and are made otherwise; a primitive without texture coordinates is named and shaded without its map.
TEST(GltfConformance, NormalMapTangentsFromTheFileOrMade) {
  const std::string dir = test::scratch_dir();
  write_png_display(dir + "/bump.png", 1, 1, {0.7f, 0.5f, 1.0f});
  auto quad_scene = [&](bool with_tangents, bool with_uvs, json node) {
    GltfBuilder b;
    json attributes = json::object();
    float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
    if (with_uvs) attributes["TEXCOORD_0"] = b.add_accessor(b.add_view(uv, sizeof uv), kFloat, 4, "VEC2");
    float tangent[] = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
    if (with_tangents) attributes["TANGENT"] = b.add_accessor(b.add_view(tangent, sizeof tangent), kFloat, 4, "VEC4");
    add_quad(b, attributes, 0);
    b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}, {"scale", 0.5}}}}});
    b.doc["images"] = json::array({{{"uri", "bump.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    node["mesh"] = 0;
    b.doc["nodes"] = json::array({node});
    return load_gltf(b.write(dir, "bump"));
  };
  const Scene made = quad_scene(false, true, json::object());
  ASSERT_EQ(made.tangents.size(), made.positions.size());
  EXPECT_EQ(made.materials[0].normal_texture, 0);
  EXPECT_FLOAT_EQ(made.materials[0].normal_scale, 0.5f);
  // u grows along +x; v grows along +y, so the image's up is -y: cross(+z, +x) = +y, w = -1.
  for (const glm::vec4& t : made.tangents) {
    expect_vec3(glm::vec3(t), {1, 0, 0}, 1e-6f, "made tangent");
    EXPECT_EQ(t.w, -1.0f);
  }
  const Scene from_file = quad_scene(true, true, json::object());
  for (const glm::vec4& t : from_file.tangents) {
    expect_vec3(glm::vec3(t), {0, 1, 0}, 1e-6f, "file tangent");
    EXPECT_EQ(t.w, 1.0f);
  }
  const Scene mirrored = quad_scene(true, true, {{"scale", {1.0, -1.0, 1.0}}});
  for (const glm::vec4& t : mirrored.tangents) {
    expect_vec3(glm::vec3(t), {0, -1, 0}, 1e-6f, "mirrored tangent");
    EXPECT_EQ(t.w, -1.0f);
  }
  const Scene no_uvs = quad_scene(false, false, json::object());
  for (const glm::vec4& t : no_uvs.tangents) EXPECT_EQ(t.w, 0.0f);
  size_t named = 0;
  for (const std::string& line : no_uvs.unsupported) named += line.find("without texture coordinates") != std::string::npos;
  EXPECT_EQ(named, 1u);
}

}  // namespace
}  // namespace rcsplat
