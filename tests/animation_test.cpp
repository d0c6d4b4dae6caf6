// Camera paths (issue 42, item 1): glTF samplers against a double-precision reference written another way (Bezier
// control points for the cubic spline, the quaternion logarithm for slerp), a camera rig loaded from a glTF file,
// keyframe files, orbits, frame-name patterns, and `animate` itself against `render` at the same pose.
#include "scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "sequence/walkthrough.h"
#include "gltf_builder.h"
#include "image/image_io.h"
#include "sequence/camera_path.h"
#include "scene/gltf_loader.h"
#include "test_support.h"
#include "util/error.h"
#include "util/frame_pattern.h"

namespace rcsplat {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;
using test::json;

// Quaternions in double as (w, x, y, z), written for the test.
struct Quat {
  double w, x, y, z;
};
Quat mul(const Quat& a, const Quat& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
Quat conj(const Quat& q) { return {q.w, -q.x, -q.y, -q.z}; }
Quat unit(const Quat& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}
// q0 (q0^-1 q1)^u through the logarithm of the relative rotation: slerp along the shorter arc.
Quat slerp_by_power(Quat q0, Quat q1, double u) {
  if (q0.w * q1.w + q0.x * q1.x + q0.y * q1.y + q0.z * q1.z < 0) q1 = {-q1.w, -q1.x, -q1.y, -q1.z};
  const Quat r = mul(conj(q0), q1);
  const double s = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z), angle = std::atan2(s, r.w);
  if (s < 1e-12) return q0;
  const double k = std::sin(u * angle) / s;
  return mul(q0, {std::cos(u * angle), r.x * k, r.y * k, r.z * k});
}
glm::dvec3 rotate(const Quat& q, const glm::dvec3& v) {
  const Quat p = mul(mul(q, {0, v.x, v.y, v.z}), conj(q));
  return {p.x, p.y, p.z};
}

// De Casteljau on the Bezier control points that a Hermite segment's tangents make.
double bezier(double p0, double p1, double p2, double p3, double u) {
  const double a = p0 + u * (p1 - p0), b = p1 + u * (p2 - p1), c = p2 + u * (p3 - p2);
  const double d = a + u * (b - a), e = b + u * (c - b);
  return d + u * (e - d);
}

// The reference value of a track at t: the segment found by a linear scan, each interpolation written as above.
std::vector<double> reference_sample(const AnimationTrack& track, double t) {
  const size_t n = track.property == AnimatedProperty::rotation ? 4 : 3, keys = track.times.size();
  const bool cubic = track.interpolation == AnimationInterpolation::cubic_spline;
  auto element = [&](size_t k, size_t which, size_t c) {
    return double(track.values[((cubic ? 3 * k + which : k) * n) + c]);
  };
  const size_t mid = cubic ? 1 : 0;
  std::vector<double> out(n);
  size_t k = 0;
  if (t <= track.times[0] || t >= track.times[keys - 1]) {
    const size_t at = t <= track.times[0] ? 0 : keys - 1;
    for (size_t c = 0; c < n; ++c) out[c] = element(at, mid, c);
    return out;
  }
  while (!(t < track.times[k + 1])) ++k;
  const double h = double(track.times[k + 1]) - double(track.times[k]), u = (t - double(track.times[k])) / h;
  if (track.interpolation == AnimationInterpolation::step) {
    for (size_t c = 0; c < n; ++c) out[c] = element(k, 0, c);
  } else if (!cubic && n == 4) {
    const Quat q =
        slerp_by_power({element(k, 0, 3), element(k, 0, 0), element(k, 0, 1), element(k, 0, 2)},
                       {element(k + 1, 0, 3), element(k + 1, 0, 0), element(k + 1, 0, 1), element(k + 1, 0, 2)}, u);
    out = {q.x, q.y, q.z, q.w};
  } else if (!cubic) {
    for (size_t c = 0; c < n; ++c) out[c] = (1 - u) * element(k, 0, c) + u * element(k + 1, 0, c);
  } else {
    for (size_t c = 0; c < n; ++c)
      out[c] = bezier(element(k, 1, c), element(k, 1, c) + element(k, 2, c) * h / 3,
                      element(k + 1, 1, c) - element(k + 1, 0, c) * h / 3, element(k + 1, 1, c), u);
    if (n == 4) {
      const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
      for (double& v : out) v /= len;
    }
  }
  return out;
}

AnimationTrack random_track(std::mt19937& rng, AnimatedProperty property, AnimationInterpolation interpolation) {
  std::uniform_real_distribution<float> step(0.05f, 1.0f), value(-2.0f, 2.0f);
  AnimationTrack track;
  track.property = property;
  track.interpolation = interpolation;
  const size_t keys = 2 + rng() % 6, n = property == AnimatedProperty::rotation ? 4 : 3;
  float t = step(rng);
  for (size_t k = 0; k < keys; ++k, t += step(rng)) track.times.push_back(t);
  for (size_t k = 0; k < keys * n * (interpolation == AnimationInterpolation::cubic_spline ? 3 : 1); ++k)
    track.values.push_back(value(rng));
  if (property == AnimatedProperty::rotation && interpolation != AnimationInterpolation::cubic_spline)
    for (size_t k = 0; k < keys; ++k) {  // unit keys, as a file holds
      float* q = &track.values[k * 4];
      const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      for (int c = 0; c < 4; ++c) q[c] /= len;
    }
  return track;
}

TEST(Animation, SamplersMatchADoublePrecisionReference) {
  std::mt19937 rng(42);
  double worst = 0.0;
  for (AnimatedProperty property : {AnimatedProperty::translation, AnimatedProperty::rotation})
    for (AnimationInterpolation interpolation :
         {AnimationInterpolation::step, AnimationInterpolation::linear, AnimationInterpolation::cubic_spline})
      for (int trial = 0; trial < 50; ++trial) {
        const AnimationTrack track = random_track(rng, property, interpolation);
        std::uniform_real_distribution<double> when(0.0, double(track.times.back()) + 0.5);
        for (int s = 0; s < 40; ++s) {
          const double t = when(rng);
          const glm::vec4 got = sample_track(track, t);
          const std::vector<double> want = reference_sample(track, t);
          // q and -q are one rotation.
          double same = 0.0, flipped = 0.0;
          for (size_t c = 0; c < want.size(); ++c) {
            same = std::max(same, std::fabs(double(got[int(c)]) - want[c]));
            flipped = std::max(flipped, std::fabs(double(got[int(c)]) + want[c]));
          }
          worst = std::max(worst, property == AnimatedProperty::rotation ? std::min(same, flipped) : same);
        }
      }
  // Keys are floats; the sampler computes in double and returns floats: a few float ulps of values up to 2 or so.
  EXPECT_LT(worst, 2e-6);
}

// A quad, a boom (node 1) that turns about +y, and its child camera (node 2) that moves along a cubic spline; a
// second animation moves the quad.
struct RigScene {
  std::string path;
  AnimationTrack boom_turn, camera_move;
  glm::dvec3 boom_position{0.5, 0.5, 0.0};
};

RigScene rig_scene(const std::string& dir) {
  GltfBuilder b;
  float pos[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  uint32_t idx[] = {0, 1, 2, 0, 2, 3};
  const int p = b.add_accessor(b.add_view(pos, sizeof pos), 5126, 4, "VEC3");
  const int i = b.add_accessor(b.add_view(idx, sizeof idx), 5125, 6, "SCALAR");
  b.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", p}}}, {"indices", i}}})}}});
  RigScene scene;
  std::mt19937 rng(7);
  scene.boom_turn.property = AnimatedProperty::rotation;
  scene.boom_turn.interpolation = AnimationInterpolation::linear;
  scene.boom_turn.times = {0.0f, 1.0f, 2.5f};
  const float s = std::sqrt(0.5f);
  scene.boom_turn.values = {0, 0, 0, 1, 0, s, 0, s, 0, 1, 0, 0};  // 0, 90 and 180 degrees about +y
  scene.camera_move = random_track(rng, AnimatedProperty::translation, AnimationInterpolation::cubic_spline);
  scene.camera_move.times = {0.0f, 0.8f, 2.0f};
  scene.camera_move.values.resize(3 * 3 * 3);
  for (size_t k = 0; k < 3; ++k) scene.camera_move.values[(3 * k + 1) * 3 + 2] += 4.0f;  // in front of the quad
  auto accessor = [&](const std::vector<float>& v, const std::string& type, size_t count) {
    return b.add_accessor(b.add_view(v.data(), v.size() * sizeof(float)), 5126, count, type);
  };
  const int turn_t = accessor(scene.boom_turn.times, "SCALAR", 3), turn_v = accessor(scene.boom_turn.values, "VEC4", 3);
  const int move_t = accessor(scene.camera_move.times, "SCALAR", 3),
            move_v = accessor(scene.camera_move.values, "VEC3", 9);
  const int quad_t = accessor({0.0f, 1.0f}, "SCALAR", 2), quad_v = accessor({0, 0, 0, 0, 1, 0}, "VEC3", 2);
  b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}});
  b.doc["nodes"] = json::array({{{"name", "Quad"}, {"mesh", 0}},
                                {{"name", "Boom"}, {"translation", {0.5, 0.5, 0.0}}, {"children", {2}}},
                                {{"name", "Cam"}, {"camera", 0}}});
  b.doc["scenes"] = json::array({{{"nodes", {0, 1}}}});
  b.doc["animations"] = json::array(
      {{{"name", "Fly"},
        {"samplers", json::array({{{"input", turn_t}, {"output", turn_v}},
                                  {{"input", move_t}, {"output", move_v}, {"interpolation", "CUBICSPLINE"}}})},
        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}},
                                  {{"sampler", 1}, {"target", {{"node", 2}, {"path", "translation"}}}}})}},
       {{"name", "Slide"},
        {"samplers", json::array({{{"input", quad_t}, {"output", quad_v}, {"interpolation", "STEP"}}})},
        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  scene.path = b.write(dir, "rig");
  return scene;
}

TEST(Animation, AGltfCameraFollowsItsNodeAndItsParent) {
  const RigScene rig = rig_scene(test::scratch_dir());
  const Scene scene = load_gltf(rig.path);
  const CameraPath path = gltf_camera_path(scene, 0, 0);
  EXPECT_NEAR(path.duration, 2.5, 1e-6);
  double worst = 0.0;
  for (double t = -0.25; t <= 2.75; t += 0.0625) {
    const std::vector<double> r = reference_sample(rig.boom_turn, t), m = reference_sample(rig.camera_move, t);
    const Quat turn{r[3], r[0], r[1], r[2]};
    const glm::dvec3 eye = rig.boom_position + rotate(turn, {m[0], m[1], m[2]});
    const glm::dvec3 forward = rotate(turn, {0, 0, -1}), up = rotate(turn, {0, 1, 0});
    const CameraPose pose = path.at(t);
    worst =
        std::max({worst, glm::length(glm::dvec3(pose.eye) - eye),
                  glm::length(glm::dvec3(pose.target - pose.eye) - forward), glm::length(glm::dvec3(pose.up) - up)});
    EXPECT_FALSE(pose.fov_degrees) << "the camera keeps its own field of view";
  }
  EXPECT_LT(worst, 1e-5);
  // The second animation moves the quad: refused, naming the animation and the node.
  try {
    gltf_camera_path(scene, 0, 1);
    ADD_FAILURE() << "an animation that moves a mesh was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("animations[1] 'Slide' moves nodes[0] 'Quad'"), std::string::npos) << message;
  }
  EXPECT_THROW(gltf_camera_path(scene, 0, 2), Error);
}

// A quad in front of a still camera, with a floor behind it, and an animation that slides the quad by `slide` along x
// at t = 1 s (STEP); slide given with `moving` false: the quad stands there, no animation.
std::string sliding_quad_scene(const std::string& dir, const std::string& name, float slide, bool moving) {
  GltfBuilder b;
  float pos[] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0,
                 -3, -3, -1, 3, -3, -1, 3, 3, -1, -3, 3, -1};
  uint32_t idx[] = {0, 1, 2, 0, 2, 3};
  const int p = b.add_accessor(b.add_view(pos, sizeof pos), 5126, 4, "VEC3");
  const int wall = b.add_accessor(b.add_view(pos + 12, 12 * sizeof(float)), 5126, 4, "VEC3");
  const int i = b.add_accessor(b.add_view(idx, sizeof idx), 5125, 6, "SCALAR");
  b.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", p}}}, {"indices", i}}})}},
                                 {{"primitives", json::array({{{"attributes", {{"POSITION", wall}}}, {"indices", i}}})}}});
  b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.01}}}}});
  json quad = {{"name", "Quad"}, {"mesh", 0}};
  if (!moving) quad["translation"] = {slide, 0.0, 0.0};
  b.doc["nodes"] = json::array({quad, {{"name", "Wall"}, {"mesh", 1}},
                                {{"name", "Cam"}, {"camera", 0}, {"translation", {0.0, 0.0, 3.0}}}});
  b.doc["scenes"] = json::array({{{"nodes", {0, 1, 2}}}});
  if (moving) {
    const float times[] = {0.0f, 1.0f}, values[] = {0, 0, 0, slide, 0, 0};
    const int t = b.add_accessor(b.add_view(times, sizeof times), 5126, 2, "SCALAR");
    const int v = b.add_accessor(b.add_view(values, sizeof values), 5126, 2, "VEC3");
    b.doc["animations"] = json::array(
        {{{"name", "Slide"},
          {"samplers", json::array({{{"input", t}, {"output", v}, {"interpolation", "STEP"}}})},
          {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  }
  return b.write(dir, name);
}

// --cache-per-frame plays an animation that moves a mesh: each frame is the scene posed at its time, rendered as
// `render` renders that pose (the same bits as a file with the quad standing there); a cache pre-pass refuses it by
// name. Planted once: the pose not applied to the nodes (every frame the rest pose) failed the last frame's bits.
TEST(Animation, ACachePerFrameRendersAMovingScenePosedAtEachFrame) {
  const fs::path dir = test::scratch_dir();
  const std::string moving = sliding_quad_scene(dir.string(), "moving", 0.6f, true);
  WalkthroughRequest o;
  o.render.scene_path = moving;
  o.render.settings = test::one_bounce_one_sample();
  o.render.settings.width = o.render.settings.height = 32;
  o.fps = 2.0;
  o.cache = CacheMode::per_frame;
  o.render.outputs = {(dir / "slide_%d.exr").string()};
  ASSERT_NO_THROW(render_walkthrough(o));
  EXPECT_TRUE(fs::exists(dir / "slide_2.exr")) << "the animation lasts 1 s: frames 0 to 2";
  EXPECT_FALSE(fs::exists(dir / "slide_3.exr"));
  int w = 0, h = 0;
  const std::vector<float> before = read_exr_rgb((dir / "slide_0.exr").string(), w, h);
  EXPECT_EQ(read_exr_rgb((dir / "slide_1.exr").string(), w, h), before) << "STEP: still at rest at t = 0.5 s";
  const std::vector<float> after = read_exr_rgb((dir / "slide_2.exr").string(), w, h);
  EXPECT_NE(after, before);
  // `render` on a file with the quad standing there, as a user runs it.
  const test::CommandRun posed =
      test::run_rcsplat(dir.string(), {"render", sliding_quad_scene(dir.string(), "posed", 0.6f, false), "--width",
                                       "32", "--height", "32", "--bounces", "1", "--pixel-samples", "1", "-o",
                                       "posed.exr"});
  ASSERT_EQ(posed.exit_code, 0) << posed.output;
  EXPECT_EQ(read_exr_rgb((dir / "posed.exr").string(), w, h), after);

  // A farm's pre-pass, merge and fixed frames follow a moving scene too: tests/moving_scene_test.cpp.
}

TEST(Animation, KeyframeFilesAreReadLineByLineAndRefusedByLine) {
  const std::string good =
      "# t  eye       target   up     fov\n"
      "0    0 1 5     0 1 0    0 1 0  40\n"
      "\n"
      "1.5  1 1 5     0 1 0    0 1 0  50  # a comment\n";
  const std::vector<CameraKey> keys = parse_camera_keys(good, "walk.txt");
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[1].time, 1.5);
  EXPECT_EQ(keys[1].fov_degrees, 50.0);
  auto expect_refused = [](const std::string& text, const std::string& fragment) {
    try {
      parse_camera_keys(text, "walk.txt");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_refused("0 0 1 5 0 1 0 0 1 0 40\n0 1 1 5 0 1 0 0 1 0 40\n", "walk.txt: line 2: time 0");
  expect_refused("0 0 1 5 0 1 0 0 1 0\n", "walk.txt: line 1: 10 numbers where a key has 11");
  expect_refused("0 0 1 5 0 1 0 0 1 0 4O\n", "walk.txt: line 1: '4O' is not a finite number");
  expect_refused("0 0 1 5 0 1 0 0 1 0 nan\n", "'nan' is not a finite number");
  expect_refused("0 0 1 5 0 1 5 0 1 0 40\n", "line 1: the eye, target and up do not define a view");
  expect_refused("0 0 1 5 0 1 0 0 0 1 40\n", "line 1: the eye, target and up do not define a view");
  expect_refused("0 0 1 5 0 1 0 0 1 0 180\n", "field of view");
  expect_refused("# nothing\n", "walk.txt: no keys");
}

TEST(Animation, KeyframePathsPassThroughTheKeysAndKeepUniformMotion) {
  // Keys on a line at one speed but unevenly spaced in time: tangents over time make the motion exactly uniform.
  std::vector<CameraKey> keys;
  for (double t : {0.0, 0.3, 1.0, 1.2, 2.0})
    keys.push_back({t, {2.0 * t, 1.0, 5.0}, {2.0 * t, 1.0, 0.0}, {0, 1, 0}, 30 + 10 * t});
  const CameraPath path = keyframe_camera_path(keys, "line");
  for (double t = 0.0; t <= 2.0; t += 0.05) {
    const CameraPose pose = path.at(t);
    EXPECT_NEAR(pose.eye.x, 2.0 * t, 1e-5) << t;
    EXPECT_NEAR(pose.target.x, 2.0 * t, 1e-5) << t;
    EXPECT_NEAR(*pose.fov_degrees, 30 + 10 * t, 1e-4) << t;
  }
  // Uneven keys: through every key, and the velocity continuous across an interior key.
  keys = {{0.0, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40},
          {1.0, {3, 1, 4}, {0, 0, 0}, {0, 1, 0}, 40},
          {1.5, {2, 3, 1}, {0, 0, 0}, {0, 1, 0}, 40},
          {3.0, {-1, 0, 2}, {0, 0, 0}, {0, 1, 0}, 40}};
  const CameraPath bent = keyframe_camera_path(keys, "bent");
  for (const CameraKey& k : keys) EXPECT_LT(glm::length(glm::dvec3(bent.at(k.time).eye) - k.eye), 1e-5);
  const double h = 1e-3;
  for (double t : {1.0, 1.5}) {
    const glm::dvec3 before = (glm::dvec3(bent.at(t).eye) - glm::dvec3(bent.at(t - h).eye)) / h;
    const glm::dvec3 after = (glm::dvec3(bent.at(t + h).eye) - glm::dvec3(bent.at(t).eye)) / h;
    EXPECT_LT(glm::length(after - before), 0.05 * glm::length(before)) << "a kink at key time " << t;
  }
}

TEST(Animation, AnOrbitKeepsHeightAndDistanceAndTurnsCounterClockwiseSeenFromAbove) {
  SceneCamera start;
  start.eye = {1.0f, 2.0f, 6.0f};
  start.target = {1.0f, 0.5f, 1.0f};
  start.up = {0.0f, 1.0f, 0.0f};
  const CameraPath orbit = orbit_camera_path(start, 8.0);
  EXPECT_EQ(orbit.duration, 8.0);
  for (double t = 0.0; t <= 8.0; t += 0.5) {
    const glm::vec3 eye = orbit.at(t).eye;
    EXPECT_NEAR(eye.y, 2.0f, 1e-5f);
    EXPECT_NEAR(std::hypot(eye.x - 1.0f, eye.z - 1.0f), 5.0f, 1e-5f);
  }
  const glm::vec3 quarter = orbit.at(2.0).eye;  // from +z toward +x: counter-clockwise about +y
  EXPECT_NEAR(quarter.x, 6.0f, 1e-5f);
  EXPECT_NEAR(quarter.z, 1.0f, 1e-5f);
  EXPECT_LT(glm::length(orbit.at(8.0).eye - start.eye), 1e-4f);
  SceneCamera down = start;
  down.eye = {1.0f, 6.0f, 1.0f};
  down.up = {0.0f, 1.0f, 0.0f};
  EXPECT_THROW(orbit_camera_path(down, 8.0), Error);
}

TEST(Animation, FramePatternsNameEachFrame) {
  EXPECT_EQ(FramePattern("frames/%04d.exr", "-o").path(7), "frames/0007.exr");
  EXPECT_EQ(FramePattern("f%d.png", "-o").path(12345), "f12345.png");
  EXPECT_EQ(FramePattern("100%%_%03d.exr", "-o").path(5), "100%_005.exr");
  for (const char* bad : {"frame.exr", "%04d_%04d.exr", "%s.exr", "50%.exr", "%4d.exr", "%0d.exr"})
    EXPECT_THROW(FramePattern(bad, "-o"), Error) << bad;
}

// `animate` renders each frame as `render` does at the frame's pose, and with a cache per frame a still camera
// renders the same bits every frame.
TEST(Animation, AnimateRendersEachFrameAsRenderDoesAtItsPose) {
  const fs::path dir = test::scratch_dir();
  test::write_file((dir / "still.txt").string(), "0 0 1 3.5 0 1 0 0 1 0 40\n1 0 1 3.5 0 1 0 0 1 0 40\n");
  test::write_file((dir / "move.txt").string(), "0 -0.3 1 3.5 0 1 0 0 1 0 40\n2 0.3 1.1 3.4 0 1 0 0 1 0 45\n");
  WalkthroughRequest o;
  o.render.settings = test::one_bounce_one_sample();
  o.render.settings.width = 40;
  o.render.settings.height = 40;
  o.fps = 2.0;
  o.render.outputs = {(dir / "still_%02d.exr").string()};
  o.keyframes = (dir / "still.txt").string();
  o.stats_path = (dir / "still.csv").string();
  ASSERT_NO_THROW(render_walkthrough(o));
  int w = 0, h = 0;
  const std::vector<float> first = read_exr_rgb((dir / "still_00.exr").string(), w, h);
  for (const char* later : {"still_01.exr", "still_02.exr"})
    EXPECT_EQ(read_exr_rgb((dir / later).string(), w, h), first) << later;
  std::ifstream csv(o.stats_path);
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 4) << "a header and a row a frame";

  o.keyframes = (dir / "move.txt").string();
  o.render.outputs = {(dir / "move_%d.exr").string()};
  o.first_frame = 1;
  o.last_frame = 2;
  o.stats_path.clear();
  ASSERT_NO_THROW(render_walkthrough(o));
  EXPECT_FALSE(fs::exists(dir / "move_0.exr"));
  EXPECT_FALSE(fs::exists(dir / "move_3.exr"));
  const CameraPose pose = read_keyframe_camera_path(o.keyframes).at(1.0);  // frame 2 at 2 frames a second
  // `render` from that pose, as a user runs it.
  const CameraOverrides view = pose.overrides();
  auto triple = [](const std::optional<glm::vec3>& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", double(v->x), double(v->y), double(v->z));
    return std::string(text);
  };
  char fov[32];
  std::snprintf(fov, sizeof fov, "%.9g", double(*view.fov_degrees));
  const test::CommandRun still = test::run_rcsplat(
      dir.string(), {"render", "--width", "40", "--height", "40", "--bounces", "1", "--pixel-samples", "1", "--eye",
                     triple(view.eye), "--target", triple(view.target), "--up", triple(view.up), "--fov", fov, "-o",
                     "render.exr"});
  ASSERT_EQ(still.exit_code, 0) << still.output;
  EXPECT_EQ(read_exr_rgb((dir / "move_2.exr").string(), w, h), read_exr_rgb((dir / "render.exr").string(), w, h));
  EXPECT_NE(read_exr_rgb((dir / "move_1.exr").string(), w, h), read_exr_rgb((dir / "render.exr").string(), w, h));

  // Refused before any frame: no output.
  o.mp4_path = (dir / "preview.mp4").string();
  o.render.outputs = {(dir / "bad_%d.exr").string()};
  EXPECT_THROW(render_walkthrough(o), Error);  // --mp4 without PNG frames
  o.mp4_path.clear();
  o.orbit_seconds = 4.0;
  EXPECT_THROW(render_walkthrough(o), Error);  // --keyframes and --orbit
  EXPECT_FALSE(fs::exists(dir / "bad_1.exr"));
}

// --mp4 through the real ffmpeg (scripts/install-debian-packages.sh installs it): one video frame a PNG frame.
TEST(Animation, AnimateWritesAnMp4PreviewWithFfmpeg) {
  const fs::path dir = test::scratch_dir();
  WalkthroughRequest o;
  o.render.settings = test::one_bounce_one_sample();
  o.render.settings.width = 30;  // odd sizes: padded to even ones for H.264
  o.render.settings.height = 25;
  o.orbit_seconds = 1.0;
  o.orbit_degrees = 20.0;
  o.fps = 3.0;
  o.render.outputs = {(dir / "orbit_%03d.png").string()};
  o.mp4_path = (dir / "orbit.mp4").string();
  ASSERT_NO_THROW(render_walkthrough(o)) << "is ffmpeg installed (scripts/install-debian-packages.sh)?";
  for (int f = 0; f < 4; ++f) EXPECT_TRUE(fs::exists(dir / ("orbit_00" + std::to_string(f) + ".png")));
  const std::string probe =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height -of csv=p=0 '" +
      o.mp4_path + "'";
  FILE* pipe = popen(probe.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char text[128] = {};
  const size_t got = fread(text, 1, sizeof text - 1, pipe);
  pclose(pipe);
  EXPECT_EQ(std::string(text, got), "30,26,4\n");
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << "left " << entry.path();
}

}  // namespace
}  // namespace rcsplat
