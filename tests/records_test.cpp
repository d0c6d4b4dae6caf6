// The record kernel (kernels/records.cl) against the host's double-precision records (same strata and random numbers,
// written independently), and its gradients against finite differences of its own irradiance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>

#include "pass_probe.h"
#include "reference/host_records.h"
#include "cache/hsh_rotation.h"
#include "cache/light_guide.h"
#include "brdf_reference.h"
#include "cache_test_scenes.h"
#include "corridor_scene.h"
#include "gap_room_scene.h"
#include "hsh_reference.h"
#include "lobed_cornell_box.h"
#include "kernels/hsh.h"
#include "kernels/low_discrepancy.h"
#include "passes/gbuffer_pass.h"
#include "passes/glossy_pass.h"
#include "passes/hsh_record_pass.h"
#include "passes/light_guide_pass.h"
#include "passes/record_pass.h"
#include "render/camera.h"
#include "scene/cornell_box.h"
#include "scene/scene_frame.h"
#include "util/error.h"
#include "util/ray_offset.h"
#include "kernels/counter_random.h"

namespace rcsplat {
namespace {

using glm::dvec3;
using glm::vec3;

GBufferSample sample_at(vec3 p, vec3 n) {
  GBufferSample g{};
  for (int i = 0; i < 3; ++i) {
    g.position[i] = p[i];
    g.normal[i] = n[i];
    g.geometric_normal[i] = n[i];
    g.albedo[i] = 1.0f;
  }
  g.triangle = 0;
  return g;
}

// A camera whose pixels are so small and radius clamps so wide that R is Ward's harmonic mean distance.
CameraParams tiny_pixel_camera() {
  CameraParams c{};
  c.forward[2] = -1.0f;
  c.right[0] = 1.0f;
  c.up[1] = 1.0f;
  c.eye[2] = 1.0f;
  c.tan_half_fov_y = 1e-3f;
  c.aspect = 1.0f;
  c.width = c.height = 1000;
  return c;
}

// Runs the record kernel at one point (keyed as pixel 0, so every call draws the same random numbers).
CacheRecord device_record(RecordPass& pass, vec3 p, vec3 n, const HemisphereParams& hp) {
  GpuContext& gpu = test::gpu();
  CameraParams camera = tiny_pixel_camera();
  GBufferView view{gpu.upload(std::vector<GBufferSample>{sample_at(p, n)}), gpu.upload(std::vector<CameraParams>{camera}),
                   1, 1};
  cl::Buffer candidates = gpu.upload(std::vector<uint32_t>{0});
  pass.compute(view, candidates, 1, 0, hp);
  return pass.download(0, 1)[0];
}

HemisphereParams hemisphere(unsigned m, unsigned n) {
  HemisphereParams hp{};
  hp.theta_strata = m;
  hp.phi_strata = n;
  hp.seed = 7;
  hp.min_radius_pixels = 1e-6f;
  hp.max_radius_pixels = 1e9f;
  return hp;
}

double irradiance_r(const CacheRecord& r) { return r.irradiance[0]; }

// The G-buffer of the scene's first camera at w x h, run on `pass` (which keeps it for the record pass) and downloaded.
std::vector<GBufferSample> camera_gbuffer(GBufferPass& pass, const Scene& scene, int w, int h) {
  pass.run(camera_params(choose_camera(scene, 0, {}), w, h));
  return pass.download();
}

// The 8 x 16 hemisphere of the tests below, with the renderer's default radius clamps.
HemisphereParams clamped_hemisphere() {
  HemisphereParams hp = hemisphere(8, 16);
  hp.min_radius_pixels = 3.0f;
  hp.max_radius_pixels = 20.0f;
  return hp;
}

// The host's double-precision record at a G-buffer sample (its position and both normals).
HostRecord host_record_at(const test::TwinScene& twin, const GBufferSample& s, uint32_t pixel, double pixel_size,
                          const HemisphereParams& hp, const std::vector<GuideCluster>& guide) {
  vec3 p(s.position[0], s.position[1], s.position[2]), n(s.normal[0], s.normal[1], s.normal[2]);
  vec3 ng(s.geometric_normal[0], s.geometric_normal[1], s.geometric_normal[2]);
  return compute_host_record(twin.shading, p, n, ng, pixel, pixel_size, hp, guide);
}

// count pixels (repeats allowed) drawn at random among those that see geometry.
std::vector<uint32_t> random_covered_pixels(const std::vector<GBufferSample>& g, size_t count, unsigned seed) {
  std::vector<uint32_t> pixels;
  std::mt19937 rng(seed);
  while (pixels.size() < count) {
    uint32_t p = rng() % uint32_t(g.size());
    if (g[p].triangle >= 0) pixels.push_back(p);
  }
  return pixels;
}

// The record kernel against compute_host_record on 200 random pixels of the scene's camera view; with a light guide
// (photons from the scene's lights, clustered), guided rays too. Returns how many records took guided rays.
size_t expect_records_match_host(const Scene& scene, bool guided, const HemisphereParams& hp_in = clamped_hemisphere(),
                                 double radius_tolerance = 1e-4) {
  test::TwinScene twin(scene);
  GpuContext& gpu = test::gpu();
  GBufferPass gbuffer(gpu, twin.device);
  std::vector<GBufferSample> g = camera_gbuffer(gbuffer, twin.scene, 48, 48);
  std::vector<uint32_t> pixels = random_covered_pixels(g, 200, 3);
  HemisphereParams hp = hp_in;
  RecordPass pass(gpu, twin.device, hp.theta_strata);
  std::vector<GuideCluster> guide;
  if (guided) {
    guide = cluster_photons(LightGuidePass(gpu, twin.device).shoot(1u << 14, 5), GUIDE_MAX_CLUSTERS);
    hp.guide_rays = 32;
    hp.guide_clusters = uint32_t(guide.size());
    pass.set_light_guide(guide, hp.guide_rays);
  }
  pass.compute(gbuffer.view(), gpu.upload(pixels), uint32_t(pixels.size()), 0, hp);
  std::vector<CacheRecord> device = pass.download(0, pixels.size());
  size_t with_guided_rays = 0;

  // Float directions and hit points differ from double ones by ~1e-7: a ray grazing an edge may land elsewhere, so a
  // few records may differ by one ray's share; the bulk must agree to float precision.
  std::vector<double> e_err, r_err, g_err, h_err, rel_err;
  size_t unclamped = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    HostRecord host = host_record_at(twin, g[pixels[i]], pixels[i], device[i].pixel_size, hp, guide);
    with_guided_rays += host.rays > hp.theta_strata * hp.phi_strata;
    EXPECT_EQ(device[i].pixel, int(pixels[i]));
    double e_scale = std::max({host.irradiance.x, host.irradiance.y, host.irradiance.z, 1e-6});
    double e_diff = 0, g_diff = 0, g_scale = 1e-9;
    for (int c = 0; c < 3; ++c) {
      e_diff = std::max(e_diff, std::abs(device[i].irradiance[c] - host.irradiance[c]));
      for (int a = 0; a < 3; ++a) {
        g_diff = std::max(g_diff, std::abs(device[i].grad_translation[3 * a + c] - host.grad_translation[size_t(a)][c]));
        g_diff = std::max(g_diff, std::abs(device[i].grad_rotation[3 * a + c] - host.grad_rotation[size_t(a)][c]) /
                                      device[i].radius);
        g_scale = std::max(g_scale, std::abs(host.grad_translation[size_t(a)][c]));
      }
    }
    e_err.push_back(e_diff / e_scale);
    if (std::isinf(host.relative_error) || std::isinf(device[i].relative_error))
      rel_err.push_back(std::isinf(host.relative_error) && std::isinf(device[i].relative_error) ? 0.0 : 1.0);
    else
      rel_err.push_back(std::abs(device[i].relative_error - host.relative_error) / std::max(host.relative_error, 1e-6));
    r_err.push_back(std::abs(device[i].radius - host.radius) / host.radius);
    double pixel = device[i].pixel_size;
    unclamped += host.radius > 1.001 * hp.min_radius_pixels * pixel && host.radius < 0.999 * hp.max_radius_pixels * pixel;
    for (size_t s = 0; s < host.horizon.size(); ++s) {
      double h = host.horizon[s], d = device[i].horizon[s];
      h_err.push_back(std::isinf(h) || std::isinf(d) ? (std::isinf(h) && std::isinf(d) ? 0.0 : 1.0) : std::abs(d - h) / h);
    }
    g_err.push_back(g_diff / std::max(g_scale, e_scale / host.radius));
  }
  auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[size_t(q * double(v.size() - 1))];
  };
  // Guided terms span more decades (a tiny cone's 1 / pdf against a stratum's), so float sums round a little more.
  EXPECT_LT(quantile(e_err, 0.5), guided ? 3e-5 : 1e-5);
  EXPECT_LT(quantile(e_err, 0.95), 1e-3);
  EXPECT_LT(quantile(r_err, 0.95), radius_tolerance);
  // The strata's relative error (adaptive rays): differences of neighbouring strata, so float rounds a little more.
  // Measured: median 1.4e-7, 95% 6e-7 (guided: 2.7e-5).
  EXPECT_LT(quantile(rel_err, 0.5), 1e-5);
  EXPECT_LT(quantile(rel_err, 0.95), 1e-3);
  std::printf("relative error of the records' relative error: median %.2e, 95%% %.2e\n", quantile(rel_err, 0.5),
              quantile(rel_err, 0.95));
  std::printf("radii inside their clamps: %zu of %zu; relative radius error: median %.2e, 95%% %.2e\n", unclamped,
              pixels.size(), quantile(r_err, 0.5), quantile(r_err, 0.95));
  if (hp.hessian_error > 0.0f) EXPECT_GT(unclamped, pixels.size() / 2) << "the Hessian's radii are barely tested";
  EXPECT_LT(quantile(h_err, 0.95), 1e-4);
  EXPECT_LT(quantile(g_err, 0.5), 1e-4);
  EXPECT_LT(quantile(g_err, 0.95), 1e-2);
  return with_guided_rays;
}

TEST(RecordKernel, MatchesHostDoublePrecisionRecords) { expect_records_match_host(make_cornell_box(), false); }

// Radii from the occlusion Hessian (kernels/record_hessian.h): the kernel's closed form per mesh edge, in float,
// against the host's central differences of Lambert's exact form factors of the same mesh, in double. Clamps wide
// open, so that the radii compared are the Hessian's own. Measured: relative radius error median 1.4e-7, 95% 8e-7
// (float hit points; fourth roots quarter a curvature's relative error), hence 1e-5. The recurrences taken from an
// edge's far end instead gave 0.46 at the 95% quantile.
TEST(RecordKernel, HessianRadiiMatchHostFiniteDifferences) {
  // 8 x 16 strata give a 4 x 4 mesh (every second row, every fourth column); 6 x 10 a 6 x 5 one (every row).
  for (auto [m, n] : {std::pair{8u, 16u}, std::pair{6u, 10u}}) {
    HemisphereParams hp = hemisphere(m, n);
    hp.min_radius_pixels = 1e-3f;
    hp.max_radius_pixels = 1e3f;
    hp.hessian_error = 1000.0f;
    expect_records_match_host(make_cornell_box(), false, hp, 1e-5);
  }
}

// The corridor lit by a small bright patch (issue 10), in its own device frame as render() would trace it: the light
// guide's cones, ray directions and balance-heuristic weights must match the host's double-precision ones.
TEST(RecordKernel, GuidedRaysMatchHostDoublePrecisionRecords) {
  const Scene corridor = test::bright_patch_corridor();
  size_t guided = expect_records_match_host(SceneFrame::fitted(corridor).device_scene(corridor), true);
  std::printf("%zu of 200 records took guided rays\n", guided);
  EXPECT_GT(guided, 100u);
}

// The record trace's shape is the device's choice (a ray per work-item on a GPU, 32 samples on PoCL, launches of at
// most record_samples_per_launch samples, one kernel or the trace split into hits and shading); the reduction sums each
// record's samples in one fixed order, so every shape must give the same records, bit for bit, guided rays included.
TEST(RecordKernel, SameRecordsWhateverTheTraceShape) {
  const Scene corridor = test::bright_patch_corridor();
  test::TwinScene twin(SceneFrame::fitted(corridor).device_scene(corridor));
  GpuContext& gpu = test::gpu();
  GBufferPass gbuffer(gpu, twin.device);
  std::vector<GBufferSample> g = camera_gbuffer(gbuffer, twin.scene, 48, 48);
  std::vector<uint32_t> pixels = random_covered_pixels(g, 100, 5);
  HemisphereParams hp = clamped_hemisphere();
  std::vector<GuideCluster> guide = cluster_photons(LightGuidePass(gpu, twin.device).shoot(1u << 14, 5), GUIDE_MAX_CLUSTERS);
  hp.guide_rays = 16;
  hp.guide_clusters = uint32_t(guide.size());
  const GroupSizes device_choice = gpu.groups();
  auto records_with = [&](size_t samples_per_item, size_t samples_per_launch, RecordTrace trace, unsigned bounces) {
    GroupSizes shape = device_choice;
    shape.record_samples_per_item = samples_per_item;
    shape.record_samples_per_launch = samples_per_launch;
    shape.record_trace = trace;
    test::PassProbe::set_groups(gpu, shape);
    RecordPass pass(gpu, twin.device, hp.theta_strata);
    pass.begin_frame(nullptr, bounces);
    pass.set_light_guide(guide, hp.guide_rays);
    pass.compute(gbuffer.view(), gpu.upload(pixels), uint32_t(pixels.size()), 0, hp);
    test::PassProbe::set_groups(gpu, device_choice);
    // The wavefront's rounds foresee every ray its shading asks for: none is traced in a round that reads answers.
    EXPECT_EQ(pass.rays_traced_late(), 0u) << record_trace_name(trace) << ", " << bounces << " bounces";
    return std::make_pair(pass.download(0, pixels.size()), pass.rays_cast());
  };
  size_t per_record = size_t(hp.theta_strata) * hp.phi_strata + hp.guide_rays;
  struct Shape {
    size_t per_item, per_launch;
    RecordTrace trace;
  };
  // The continued path (3 bounces) takes the shading's every step after the hit; the wavefront queues it.
  for (unsigned bounces : {1u, 3u}) {
    // A ray a work-item, as a GPU takes them.
    const auto [expected, expected_rays] = records_with(1, size_t(1) << 21, RecordTrace::fused, bounces);
    for (Shape shape : {Shape{32, size_t(1) << 21, RecordTrace::fused}, Shape{7, 3 * per_record, RecordTrace::fused},
                        Shape{per_record, per_record / 2, RecordTrace::fused},
                        Shape{1, size_t(1) << 21, RecordTrace::split}, Shape{7, 3 * per_record, RecordTrace::split},
                        Shape{1, size_t(1) << 21, RecordTrace::wavefront},
                        Shape{7, 3 * per_record, RecordTrace::wavefront}}) {
      std::ostringstream label;
      label << bounces << " bounces, " << shape.per_item << " samples per work-item, " << shape.per_launch
            << " per launch, the trace " << record_trace_name(shape.trace);
      const auto [records, rays] = records_with(shape.per_item, shape.per_launch, shape.trace, bounces);
      EXPECT_EQ(rays, expected_rays) << label.str();
      ASSERT_EQ(records.size(), expected.size());
      for (size_t i = 0; i < records.size(); ++i)
        ASSERT_EQ(std::memcmp(&records[i], &expected[i], sizeof(CacheRecord)), 0)
            << "record " << i << " differs with " << label.str();
    }
  }
}

// A frame rendered with the record trace (and the glossy pass) in this shape, the device's choice restored after.
RenderedImage frame_traced_as(RecordTrace trace, const Scene& scene, const RenderSettings& settings) {
  GpuContext& gpu = test::gpu();
  const GroupSizes device_choice = gpu.groups();
  GroupSizes shape = device_choice;
  shape.record_trace = trace;
  test::PassProbe::set_groups(gpu, shape);
  RenderedImage image = render(gpu, scene, settings);
  test::PassProbe::set_groups(gpu, device_choice);
  return image;
}

// The same with the photon map standing for the later bounces (the render defaults): the map reads at long rays'
// hits, short rays take a step first and read it without its last landing, and where the map is thin paths go on, so
// the wavefront queues both kinds of path. In the built-in Cornell box the map is dense (short rays read it: 4 radii
// make more of them), in the room lit through a gap (tests/gap_room_scene.h) thin where the camera looks. The whole
// frame the same bits whatever the trace's shape, its ray count too.
TEST(RecordKernel, SameFrameWhateverTheTraceShapeWithAPhotonMap) {
  RenderSettings settings;
  settings.width = 48;
  settings.height = 36;
  settings.bounces = 4;
  settings.bounce_method = BounceMethod::photons;
  settings.short_ray_paths = 4.0f;
  const std::pair<const char*, Scene> scenes[] = {{"Cornell box", make_cornell_box()},
                                                  {"gap room", test::gap_lit_room()}};
  for (const auto& [name, scene] : scenes) {
    // The split shape's shading is the one kernel's with the hits read from a buffer: RecordKernel.
    // SameRecordsWhateverTheTraceShape compares it.
    const RenderedImage fused = frame_traced_as(RecordTrace::fused, scene, settings),
                        wavefront = frame_traced_as(RecordTrace::wavefront, scene, settings);
    EXPECT_EQ(wavefront.stats.irradiance.rays, fused.stats.irradiance.rays) << name;
    EXPECT_TRUE(wavefront.color == fused.color && wavefront.indirect == fused.indirect) << name;
  }
}

// Central finite differences of the kernel's own E against its Ward-Heckbert gradients, at points where the
// gradients are not bounded. Both are estimates from M x N jittered strata: the difference quotient of the same
// samples jumps where a sample crosses an edge, and the rotational gradient weights samples by tan(theta). So each
// seed gives one paired difference (analytic - finite difference), and the mean over seeds must be within four
// standard errors of zero, plus 5% of the gradient's size for the formulas' first-order bias.
struct PairedDifferences {
  std::vector<double> diff;
  double scale = 0;
  void add(double analytic, double fd) { diff.push_back(analytic - fd); }
  void expect_consistent(const std::string& what) const {
    double n = double(diff.size()), mean = 0, var = 0;
    for (double d : diff) mean += d / n;
    for (double d : diff) var += (d - mean) * (d - mean) / (n - 1);
    double se = std::sqrt(var / n);
    EXPECT_LE(std::abs(mean), 4.0 * se + 0.05 * scale) << what << ": mean difference " << mean << ", standard error "
                                                        << se << ", gradient size " << scale;
  }
};

void check_gradients(bool occluder, vec3 p) {
  test::TwinScene twin(test::floor_and_wall(occluder));
  RecordPass pass(test::gpu(), twin.device, 32);
  const vec3 n(0, 0, 1);
  const float h = 0.01f, angle = 0.01f;
  PairedDifferences translation[2], rotation[2];
  for (unsigned seed = 1; seed <= 12; ++seed) {
    HemisphereParams hp = hemisphere(32, 128);
    hp.seed = seed;
    hp.max_radius_pixels = 1e4f;  // R = 0.02 (tiny_pixel_camera's pixels are 2e-6 wide here): the bounds stay inactive
    CacheRecord r = device_record(pass, p, n, hp);
    double e = irradiance_r(r);
    ASSERT_GT(e, 0.0);
    ASSERT_LT(std::hypot(r.grad_translation[0], r.grad_translation[3]) * r.radius, 0.99 * e) << "bound active";
    ASSERT_LT(std::hypot(r.grad_rotation[0], r.grad_rotation[3]), 0.99 * e) << "bound active";
    for (int axis = 0; axis < 2; ++axis) {
      vec3 d(0.0f);
      d[axis] = h;
      double fd = (irradiance_r(device_record(pass, p + d, n, hp)) -
                   irradiance_r(device_record(pass, p - d, n, hp))) / (2.0 * h);
      translation[axis].add(r.grad_translation[3 * axis], fd);
      translation[axis].scale += std::hypot(r.grad_translation[0], r.grad_translation[3]) / 12.0;
      // Tilting n by a small angle about the axis changes E by about angle * (axis . grad_r).
      vec3 a(0.0f);
      a[axis] = 1.0f;
      vec3 tilt = glm::cross(a, n) * std::sin(angle);
      vec3 plus = glm::normalize(n * std::cos(angle) + tilt), minus = glm::normalize(n * std::cos(angle) - tilt);
      double fd_rot = (irradiance_r(device_record(pass, p, plus, hp)) -
                       irradiance_r(device_record(pass, p, minus, hp))) / (2.0 * angle);
      rotation[axis].add(r.grad_rotation[3 * axis], fd_rot);
      rotation[axis].scale += std::hypot(r.grad_rotation[0], r.grad_rotation[3]) / 12.0;
    }
  }
  for (int axis = 0; axis < 2; ++axis) {
    translation[axis].expect_consistent("translation along axis " + std::to_string(axis));
    rotation[axis].expect_consistent("rotation about axis " + std::to_string(axis));
  }
}

// Radiance records: the translational gradient of each HSH coefficient (kernels/hsh_records.cl) against central
// finite differences of the coefficient itself, paired per seed as above. The record's frame at n = +z is the world's
// (tangent_frame), so its gradient along t and b is the one along x and y.
void check_hsh_gradients(bool occluder, vec3 p) {
  test::TwinScene twin(test::floor_and_wall(occluder));
  RecordPass pass(test::gpu(), twin.device, 32, true);
  const int order = 4, n2 = order * order;
  HshRecordPass hsh(test::gpu(), order);
  const vec3 n(0, 0, 1);
  const float h = 0.01f;
  // lambda_k (red) of a record at q, and the record's floats.
  auto coefficients_at = [&](vec3 q, const HemisphereParams& hp) {
    device_record(pass, q, n, hp);
    hsh.project(pass.strata(), pass.records(), 0, 1, hp.theta_strata, hp.phi_strata);
    return hsh.download(0, 1);
  };
  const int checked[] = {hsh_index(0, 0), hsh_index(1, -1), hsh_index(1, 0), hsh_index(1, 1), hsh_index(2, 2),
                         hsh_index(3, -1)};
  std::vector<PairedDifferences> translation(2 * std::size(checked));
  for (unsigned seed = 1; seed <= 12; ++seed) {
    HemisphereParams hp = hemisphere(32, 128);
    hp.seed = seed;
    hp.max_radius_pixels = 1e4f;
    std::vector<float> at = coefficients_at(p, hp);
    for (int axis = 0; axis < 2; ++axis) {
      vec3 d(0.0f);
      d[axis] = h;
      std::vector<float> plus = coefficients_at(p + d, hp), minus = coefficients_at(p - d, hp);
      for (size_t c = 0; c < std::size(checked); ++c) {
        size_t k = size_t(checked[c]);
        double fd = (plus[3 * k] - minus[3 * k]) / (2.0 * h);
        double analytic = at[size_t(3 * n2 * (axis == 0 ? HSH_PART_GRADIENT_T : HSH_PART_GRADIENT_B)) + 3 * k];
        PairedDifferences& pd = translation[2 * c + size_t(axis)];
        pd.add(analytic, fd);
        pd.scale += std::hypot(at[size_t(3 * n2 * HSH_PART_GRADIENT_T) + 3 * k],
                               at[size_t(3 * n2 * HSH_PART_GRADIENT_B) + 3 * k]) / 12.0;
      }
    }
  }
  for (size_t c = 0; c < std::size(checked); ++c)
    for (int axis = 0; axis < 2; ++axis)
      translation[2 * c + size_t(axis)].expect_consistent("coefficient " + std::to_string(checked[c]) + " along axis " +
                                                          std::to_string(axis));
}

TEST(HshRecordGradients, MatchFiniteDifferencesNearALitWall) { check_hsh_gradients(false, vec3(-0.3f, 0.3f, 0.0f)); }

TEST(HshRecordGradients, MatchFiniteDifferencesAtAnOccluderEdge) {
  check_hsh_gradients(true, vec3(0.3f, 0.0f, 0.0f));
}

// The bound on a radiance record's gradients (kernels/hsh_records.cl bound_hsh_gradients): a record 0.005 from the lit
// wall, far inside its radius, has hit-distance gradients far above the bound, which then holds with equality per
// channel (|grad| R = |lambda|, norms over the coefficients); a record in the open floor keeps its own (below).
// Unbounded, such records extrapolated their brightest strata into hot pixels (an anti-aliased metal floor beside the
// Cornell box's tall box had relMSE 9.1e-3 on its pixels against 1.4e-4 bounded).
TEST(HshRecordGradients, BoundedByTheRadianceOverTheRadius) {
  test::TwinScene twin(test::floor_and_wall(false));
  RecordPass pass(test::gpu(), twin.device, 16, true);
  const int order = 4, n2 = order * order;
  HshRecordPass hsh(test::gpu(), order);
  // R held at 0.5 (the tiny pixel camera's 2e-6 footprint times 2.5e5), as a render's minimum reach holds a record
  // beside a wall far above its hit distances.
  HemisphereParams hp = hemisphere(16, 32);
  hp.min_radius_pixels = hp.max_radius_pixels = 2.5e5f;
  for (vec3 p : {vec3(0.995f, 0.0f, 0.0f), vec3(-5.0f, 0.0f, 0.0f)}) {
    const CacheRecord r = device_record(pass, p, vec3(0, 0, 1), hp);
    hsh.project(pass.strata(), pass.records(), 0, 1, hp.theta_strata, hp.phi_strata);
    const std::vector<float> at = hsh.download(0, 1);
    for (int c = 0; c < 3; ++c) {
      double light = 0.0, change = 0.0;
      for (int k = 0; k < n2; ++k) {
        light += std::pow(at[size_t(3 * n2 * HSH_PART_COEFFICIENTS + 3 * k + c)], 2);
        change += std::pow(at[size_t(3 * n2 * HSH_PART_GRADIENT_T + 3 * k + c)], 2) +
                  std::pow(at[size_t(3 * n2 * HSH_PART_GRADIENT_B + 3 * k + c)], 2);
      }
      const double ratio = std::sqrt(change) * r.radius / std::sqrt(light);
      std::printf("record at x = %.3f, radius %.3f, channel %d: |grad| R / |lambda| = %.5f\n", p.x, r.radius, c, ratio);
      if (p.x > 0.0f)
        EXPECT_NEAR(ratio, 1.0, 1e-4) << "beside the wall, channel " << c;
      else
        EXPECT_LT(ratio, 1.0) << "in the open, channel " << c;
    }
  }
}

// Radiance records with a light guide: every coefficient lambda_k (kernels/hsh_records.cl, order 4) against the
// host's double-precision projection of the host's own record (tests/reference/host_records.h): each stratum's share of the
// light (the balance-heuristic weight beside the guide's rays, which the pixels take: kernels/glossy.cl guide_share)
// times the exact integral of H_k over the stratum (Gauss-Legendre in cos(theta) and phi, 8 x 8 nodes, exact for
// these polynomials in cos(theta) and nearly so in phi). In the Cornell box, where every record's strata see light
// and about a quarter of the records see some of the guide's clusters (in the corridor most strata see nothing at
// all: zero on both sides, which would test little).
TEST(HshRecordKernel, GuidedCoefficientsMatchHostDoublePrecision) {
  test::TwinScene twin(make_cornell_box());
  GpuContext& gpu = test::gpu();
  GBufferPass gbuffer(gpu, twin.device);
  std::vector<GBufferSample> g = camera_gbuffer(gbuffer, twin.scene, 48, 48);
  std::vector<uint32_t> pixels = random_covered_pixels(g, 64, 11);
  HemisphereParams hp = clamped_hemisphere();
  hp.guide_rays = 32;
  const std::vector<GuideCluster> guide =
      cluster_photons(LightGuidePass(gpu, twin.device).shoot(1u << 14, 5), GUIDE_MAX_CLUSTERS);
  hp.guide_clusters = uint32_t(guide.size());
  RecordPass pass(gpu, twin.device, hp.theta_strata, true);
  pass.set_light_guide(guide, hp.guide_rays);
  pass.compute(gbuffer.view(), gpu.upload(pixels), uint32_t(pixels.size()), 0, hp);
  const int order = 4, n2 = order * order, M = int(hp.theta_strata), N = int(hp.phi_strata);
  HshRecordPass hsh(gpu, order);
  hsh.project(pass.strata(), pass.records(), 0, uint32_t(pixels.size()), hp.theta_strata, hp.phi_strata);
  const std::vector<float> device = hsh.download(0, uint32_t(pixels.size()));
  const std::vector<CacheRecord> records = pass.download(0, pixels.size());

  // The integral of H_k over each stratum (rows equal in sin^2 theta, columns in phi), the same for every record.
  std::vector<double> stratum_integral(size_t(M * N * n2), 0.0), nodes, weights;
  for (int j = 0; j < M; ++j)
    for (int k = 0; k < N; ++k) {
      double cos_hi = std::sqrt(1.0 - double(j) / M), cos_lo = std::sqrt(1.0 - double(j + 1) / M);
      double phi_lo = 2.0 * M_PI * k / N, phi_hi = 2.0 * M_PI * (k + 1) / N;
      std::vector<double> c_nodes, c_weights, p_nodes, p_weights;
      gauss_legendre(8, cos_lo, cos_hi, c_nodes, c_weights);
      gauss_legendre(8, phi_lo, phi_hi, p_nodes, p_weights);
      for (size_t a = 0; a < c_nodes.size(); ++a)
        for (size_t b = 0; b < p_nodes.size(); ++b)
          for (int l = 0; l < order; ++l)
            for (int m = -l; m <= l; ++m)
              stratum_integral[size_t((j * N + k) * n2 + hsh_index(l, m))] +=
                  c_weights[a] * p_weights[b] * reference_hsh(l, m, c_nodes[a], p_nodes[b]);
    }

  std::vector<double> errors;
  size_t with_guided_rays = 0;  // records whose host twin cast guided rays: those whose strata are weighted
  for (size_t i = 0; i < pixels.size(); ++i) {
    HostRecord host = host_record_at(twin, g[pixels[i]], pixels[i], records[i].pixel_size, hp, guide);
    with_guided_rays += host.rays > hp.theta_strata * hp.phi_strata;
    std::vector<double> want(size_t(n2), 0.0);
    for (size_t st = 0; st < host.strata_radiance.size(); ++st)
      for (int k = 0; k < n2; ++k) want[size_t(k)] += host.strata_radiance[st].x * stratum_integral[st * size_t(n2) + size_t(k)];
    double scale = 1e-9, diff = 0.0;
    for (int k = 0; k < n2; ++k) {
      scale = std::max(scale, std::abs(want[size_t(k)]));
      diff = std::max(diff, std::abs(double(device[i * size_t(HSH_RECORD_PARTS * 3 * n2) + 3 * size_t(k)]) - want[size_t(k)]));
    }
    errors.push_back(diff / scale);
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p95 = errors[size_t(0.95 * double(errors.size() - 1))];
  std::printf("%zu of %zu radiance records see a cone; coefficient error relative to the largest: median %.2e, "
              "95%% %.2e\n", with_guided_rays, pixels.size(), median, p95);
  EXPECT_GT(with_guided_rays, pixels.size() / 8);  // 17 of 64: enough that a wrong weight shows in the 95th percentile
  // As the irradiance records above: float directions may send a grazing ray elsewhere in a few records.
  EXPECT_LT(median, 1e-4);
  EXPECT_LT(p95, 1e-2);
}

// The other half of that split (kernels/glossy.cl guide_share): at each radiance-cached pixel of the corridor with
// metal walls (roughness 0.6), the glossy pass's estimate of the light the records leave to the guide, against the
// same estimator in double on the host (the same random numbers; cones, directions and densities from
// tests/reference/host_records.h, Embree rays, the BRDF of tests/brdf_reference.h): the mean over the pixel's samples of
// f cos L n_g / (n_c p_c + n_g p_g), drawn from the records' own cones. Nearly every cone holds nearly all of the
// weight here (n_g p_g >> n_c p_c), so a weight of 1 in its place would still be off by about 1%: far above float.
TEST(GlossyKernel, GuideShareOfRadianceCachedPixelsMatchesHostDoublePrecision) {
  const Scene corridor = test::bright_patch_corridor(0.6f);
  test::TwinScene twin(SceneFrame::fitted(corridor).device_scene(corridor));
  GpuContext& gpu = test::gpu();
  const int w = 64, h = 48;
  CameraParams camera = camera_params(choose_camera(twin.scene, 0, {}), w, h);
  GBufferPass gbuffer(gpu, twin.device);
  gbuffer.run(camera);
  const std::vector<GBufferSample> g = gbuffer.download();
  const std::vector<GuideCluster> guide =
      cluster_photons(LightGuidePass(gpu, twin.device).shoot(1u << 14, 5), GUIDE_MAX_CLUSTERS);
  const unsigned samples = 16, seed = 9, record_strata = 16 * 32, record_guide_rays = 64;
  GlossyPass glossy(gpu, twin.device, false);
  glossy.run(gbuffer.view(), samples, seed, guide, record_strata, record_guide_rays);
  const std::vector<float> device = test::PassProbe::glossy_rgba(glossy);
  const unsigned share_samples = samples;
  const SceneMaterial& metal = twin.scene.materials[1];
  const brdf_reference::Material brdf{{metal.base_color.x, metal.base_color.y, metal.base_color.z}, metal.metallic,
                                      metal.roughness, metal.specular};
  const dvec3 eye(camera.eye[0], camera.eye[1], camera.eye[2]);

  std::vector<double> errors;
  size_t with_light = 0;
  for (uint32_t pixel = 0; pixel < uint32_t(w * h); ++pixel) {
    const GBufferSample& s = g[pixel];
    if (s.triangle < 0 || s.lobe != LOBE_HSH) continue;
    const vec3 pf(s.position[0], s.position[1], s.position[2]), ngf(s.geometric_normal[0], s.geometric_normal[1],
                                                                      s.geometric_normal[2]);
    const dvec3 p(pf), n(s.normal[0], s.normal[1], s.normal[2]), ng(ngf), wo_world = glm::normalize(eye - p);
    const vec3 origin = offset_ray_origin(pf, ngf);
    // A frame around n with the view in its x-z plane: the BRDF is isotropic.
    dvec3 x = glm::normalize(wo_world - glm::dot(wo_world, n) * n), y = glm::cross(n, x);
    const brdf_reference::Vec wo{glm::dot(wo_world, x), 0.0, glm::dot(wo_world, n)};
    const std::vector<HostGuideCone> cones = host_guide_cones(guide, p, n, int(record_strata));
    const uint32_t key = hash_u32(pixel ^ hash_u32(seed ^ 0x2c1b3c6du));
    double want = 0.0;
    for (unsigned k = 0; k < (cones.empty() ? 0u : share_samples); ++k) {
      float u, v, w;
      scrambled_sobol3(k, key, &u, &v, &w);
      dvec3 dir = host_guide_direction(cones, u, v, w);
      const brdf_reference::Vec wi{glm::dot(dir, x), glm::dot(dir, y), glm::dot(dir, n)};
      if (wi.z <= 0.0 || glm::dot(dir, ng) <= 0.0) continue;
      double f = brdf_reference::reference_brdf(brdf, wo, wi, false, true)[0];
      if (!(f > 0.0)) continue;
      double distance;
      dvec3 l = twin.shading.bounce_radiance(origin, glm::normalize(vec3(dir)), random01(key, k, 2),
                                             random01(key, k, 3), &distance);
      double strata_density = record_strata / M_PI * wi.z, guided = double(record_guide_rays);
      want += f * l.x * wi.z * guided / (strata_density + guided * host_guide_density(cones, dir));
    }
    want /= share_samples;
    const double got = device[4 * pixel];
    if (want == 0.0 && got == 0.0) continue;
    ++with_light;
    errors.push_back(std::abs(got - want) / std::max(std::abs(want), 1e-12));
  }
  ASSERT_GT(with_light, 100u) << "too few radiance-cached pixels see the patch";
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p95 = errors[size_t(0.95 * double(errors.size() - 1))];
  std::printf("%zu radiance-cached pixels with a guide share; relative error median %.2e, 95%% %.2e\n", with_light,
              median, p95);
  // Float directions, BRDF and distances against double: a grazing ray may land elsewhere in a few pixels.
  EXPECT_LT(median, 1e-4);
  EXPECT_LT(p95, 5e-3);
}

// The glossy pass as a wavefront (GroupSizes::record_trace: its samples traced, their first hits shaded, the paths
// going on queued and stepped a kernel a bounce, then each pixel's samples summed) against its one kernel: the same
// frame, bit for bit, with its ray count. The lobed Cornell box (a glossy floor sampled per pixel, a radiance-cached
// box) at the defaults, whose samples read the records where they land and whose radiance-cached pixels take the
// light guide's share from their own samples (guide_share), and with three bounces continued by paths that read none.
TEST(GlossyKernel, SameFrameWhateverTheTraceShape) {
  RenderSettings defaults;
  defaults.width = 40;
  defaults.height = 32;
  RenderSettings paths = defaults;
  paths.bounces = 3;
  paths.bounce_method = BounceMethod::path;
  paths.glossy_reads_records = false;
  struct Case {
    const char* name;
    Scene scene;
    RenderSettings settings;
  };
  const Case cases[] = {{"lobed Cornell box, defaults", test::cornell_box_with_lobes(0.2f, 0.5f), defaults},
                        {"lobed Cornell box, paths", test::cornell_box_with_lobes(0.2f, 0.5f), paths}};
  for (const Case& c : cases) {
    const RenderedImage fused = frame_traced_as(RecordTrace::fused, c.scene, c.settings),
                        wavefront = frame_traced_as(RecordTrace::wavefront, c.scene, c.settings);
    ASSERT_GT(fused.stats.glossy.rays, 0u) << c.name;
    EXPECT_EQ(wavefront.stats.glossy.rays, fused.stats.glossy.rays) << c.name;
    EXPECT_TRUE(wavefront.color == fused.color && wavefront.indirect == fused.indirect) << c.name;
  }
}

// The kernel keeps a column of M strata in an array sized when it is compiled: a larger M is refused, never clamped.
TEST(RecordKernel, RefusesMoreRowsThanItWasBuiltFor) {
  test::TwinScene twin(make_cornell_box());
  RecordPass pass(test::gpu(), twin.device, 8);
  EXPECT_NO_THROW(device_record(pass, vec3(0.0f), vec3(0, 1, 0), hemisphere(8, 16)));
  EXPECT_THROW(device_record(pass, vec3(0.0f), vec3(0, 1, 0), hemisphere(9, 16)), Error);
  EXPECT_THROW(device_record(pass, vec3(0.0f), vec3(0, 1, 0), hemisphere(8, HEMISPHERE_MAX_PHI_STRATA + 1)), Error);
  EXPECT_THROW(RecordPass(test::gpu(), twin.device, HEMISPHERE_MAX_THETA_STRATA + 1), Error);
}

TEST(RecordGradients, MatchFiniteDifferencesNearALitWall) { check_gradients(false, vec3(-0.3f, 0.3f, 0.0f)); }

TEST(RecordGradients, MatchFiniteDifferencesAtAnOccluderEdge) { check_gradients(true, vec3(0.3f, 0.0f, 0.0f)); }

}  // namespace
}  // namespace rcsplat
