// kernels/cache_math.h is compiled by the kernels and by the host: both must decide alike, bit for bit, or the two
// cache methods would place different records. Random inputs, many of them near the weight threshold, evaluated by a
// test kernel and by the host; and the functions against an independent double-precision reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "cache/octree_lookup.h"
#include "kernels/cache_math.h"
#include "test_support.h"

namespace rcsplat {
namespace {

using glm::dvec3;
using glm::vec3;

constexpr int kInputs = 16;   // floats per case: p, n, pk, nk, radius, accuracy, min radius, pixel size, spare
constexpr int kOutputs = 10;  // weight, usable, not in front, E (3), neighbour bound, clamped radius, pixel size, horizon

const char* kEvaluateCacheMath = R"(
#include "cache_math.h"
__kernel void evaluate_cache_math(__global const float* inputs, __global const CacheRecord* records,
                                  __global const CameraParams* camera, uint count, __global float* outputs) {
  uint i = get_global_id(0);
  if (i >= count) return;
  __global const float* in = inputs + 16 * i;
  float3 p = vload3(0, in), n = vload3(1, in), pk = vload3(2, in), nk = vload3(3, in);
  float radius = in[12], accuracy = in[13];
  __global float* out = outputs + 10 * i;
  float w = ward_weight(p, n, pk, nk, radius);
  out[0] = w;
  out[1] = record_usable(w, accuracy, p, n, pk, nk, radius) ? 1.0f : 0.0f;
  out[2] = not_in_front_of_record(p, n, pk, nk, radius) ? 1.0f : 0.0f;
  vstore3(extrapolated_irradiance(records + i, p, n), 1, out);
  float bound = neighbour_radius_bound(p, pk, radius);
  out[6] = bound;
  out[7] = neighbour_clamped_radius(radius, bound * 0.5f, in[14], in[15]);
  out[8] = pixel_world_size(camera, p);
  float3 t, b;
  tangent_frame(nk, &t, &b);
  out[9] = within_record_horizon(records + i, t, b, p) ? 1.0f : 0.0f;
}
)";

struct Case {
  float in[kInputs];
  CacheRecord record;
};

std::vector<Case> random_cases(size_t count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f), pos(0.0f, 1.0f);
  auto unit = [&] {
    vec3 v;
    do v = vec3(uni(rng), uni(rng), uni(rng));
    while (glm::length(v) < 0.1f);
    return glm::normalize(v);
  };
  std::vector<Case> cases(count);
  for (Case& c : cases) {
    std::memset(&c, 0, sizeof c);
    vec3 pk(uni(rng) * 100.0f, uni(rng) * 100.0f, uni(rng) * 100.0f), nk = unit();
    float radius = std::pow(10.0f, 2.0f * pos(rng) - 1.0f), accuracy = 0.1f + pos(rng);
    // Points around the reach a * R, with normals near the record's: many decisions close to the threshold.
    vec3 p = pk + unit() * (accuracy * radius * (0.5f + pos(rng)));
    vec3 n = glm::normalize(nk + 0.3f * pos(rng) * unit());
    for (int k = 0; k < 3; ++k) {
      c.in[k] = p[k];
      c.in[3 + k] = n[k];
      c.in[6 + k] = pk[k];
      c.in[9 + k] = nk[k];
      c.record.position[k] = pk[k];
      c.record.normal[k] = nk[k];
      c.record.irradiance[k] = std::pow(10.0f, 4.0f * pos(rng) - 2.0f);
      for (int a = 0; a < 3; ++a) {
        c.record.grad_translation[3 * a + k] = uni(rng) * c.record.irradiance[k] / radius;
        c.record.grad_rotation[3 * a + k] = uni(rng) * c.record.irradiance[k];
      }
    }
    c.record.radius = radius;
    // Horizons around the point's distance: both outcomes, some close to the boundary.
    for (float& h : c.record.horizon) h = glm::length(p - pk) * (0.5f + pos(rng));
    c.in[12] = radius;
    c.in[13] = accuracy;
    c.in[14] = 3.0f / accuracy;
    c.in[15] = 0.01f * pos(rng);
  }
  return cases;
}

CameraParams test_camera() {
  CameraParams c{};
  c.eye[0] = 3.0f;
  c.eye[2] = 250.0f;
  c.forward[2] = -1.0f;
  c.right[0] = 1.0f;
  c.up[1] = 1.0f;
  c.tan_half_fov_y = 0.4f;
  c.aspect = 1.5f;
  c.width = 960;
  c.height = 640;
  return c;
}

TEST(CacheMath, DeviceAndHostComputeTheSameBits) {
  GpuContext& gpu = test::gpu();
  std::vector<Case> cases = random_cases(20000);
  std::vector<float> inputs;
  std::vector<CacheRecord> records;
  for (const Case& c : cases) {
    inputs.insert(inputs.end(), c.in, c.in + kInputs);
    records.push_back(c.record);
  }
  CameraParams camera = test_camera();
  cl::Buffer out(gpu.context(), CL_MEM_WRITE_ONLY, cases.size() * kOutputs * sizeof(float));
  NamedKernel kernel(gpu, gpu.program_from_text("cache_math_test.cl", kEvaluateCacheMath), "evaluate_cache_math");
  // The buffers must outlive the launch: a kernel argument does not keep its buffer alive.
  cl::Buffer input_buffer = gpu.upload(inputs), record_buffer = gpu.upload(records);
  cl::Buffer camera_buffer = gpu.upload(std::vector<CameraParams>{camera});
  kernel.set_buffer<cl_float>("inputs", input_buffer)
      .set_buffer<CacheRecord>("records", record_buffer)
      .set_buffer<CameraParams>("camera", camera_buffer)
      .set("count", cl_uint(cases.size()))
      .set_buffer<cl_float>("outputs", out);
  kernel.launch(cases.size(), 64);
  gpu.queue().finish();
  std::vector<float> device = gpu.download<float>(out, cases.size() * kOutputs);

  size_t usable = 0, near_threshold = 0, weight_ulps = 0, hidden = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const float* in = cases[i].in;
    vec3 p = rc_load3(0, in), n = rc_load3(1, in), pk = rc_load3(2, in), nk = rc_load3(3, in);
    float radius = in[12], accuracy = in[13];
    float w = ward_weight(p, n, pk, nk, radius);
    float bound = neighbour_radius_bound(p, pk, radius);
    vec3 e = extrapolated_irradiance(&cases[i].record, p, n);
    vec3 t, b;
    tangent_frame(nk, &t, &b);
    const float horizon = within_record_horizon(&cases[i].record, t, b, p) ? 1.0f : 0.0f;
    hidden += horizon == 0.0f;
    float host[kOutputs] = {w,
                            record_usable(w, accuracy, p, n, pk, nk, radius) ? 1.0f : 0.0f,
                            not_in_front_of_record(p, n, pk, nk, radius) ? 1.0f : 0.0f,
                            e.x, e.y, e.z, bound,
                            neighbour_clamped_radius(radius, bound * 0.5f, in[14], in[15]),
                            pixel_world_size(&camera, p), horizon};
    const float* dev = &device[i * kOutputs];
    // Every program is built without contraction (FP_CONTRACT OFF, GpuContext) and the host with -ffp-contract=off:
    // the weight, E, the decisions, the neighbour bound and the clamped radius are the same bits on both sides. (With
    // OpenCL's default contraction, 6% of the weights and 10% of E values were an ulp apart on PoCL.)
    for (int k = 0; k < kOutputs; ++k) {
      weight_ulps += k == 0 && std::memcmp(&host[k], &dev[k], sizeof(float)) != 0;
      ASSERT_EQ(0, std::memcmp(&host[k], &dev[k], sizeof(float)))
          << "case " << i << " output " << k << ": host " << host[k] << ", device " << dev[k];
    }
    usable += host[1] > 0.0f;
    near_threshold += std::abs(w * accuracy - 1.0f) < 1e-3f;
  }
  EXPECT_GT(usable, cases.size() / 10);
  EXPECT_LT(usable, cases.size() * 4 / 5);
  EXPECT_GT(near_threshold, 10u) << "the inputs should test decisions close to the threshold";
  EXPECT_GT(hidden, cases.size() / 10) << "some points should lie beyond the records' horizons";
  EXPECT_LT(hidden, cases.size() * 9 / 10);
  RecordProperty("weights_an_ulp_apart", int(weight_ulps));
}

// The shared functions against Ward's formulas evaluated in double, away from the float rounding of the threshold.
TEST(CacheMath, MatchesWardsFormulasInDouble) {
  std::vector<Case> cases = random_cases(5000);
  for (const Case& c : cases) {
    dvec3 p = dvec3(rc_load3(0, c.in)), n = dvec3(rc_load3(1, c.in)), pk = dvec3(rc_load3(2, c.in));
    dvec3 nk = dvec3(rc_load3(3, c.in));
    double radius = c.in[12], accuracy = c.in[13];
    // sqrt(1 - n.nk) in its well-conditioned form |n - nk| / sqrt(2) (the inputs are unit to float precision only).
    double w = 1.0 / (glm::length(p - pk) / radius + glm::length(n - nk) / std::sqrt(2.0));
    w = std::min(w, double(MAX_RECORD_WEIGHT));
    float wf = ward_weight(vec3(p), vec3(n), vec3(pk), vec3(nk), float(radius));
    ASSERT_NEAR(wf, w, 1e-4 * w);
    bool usable = w * accuracy > 1.0 && glm::dot(n, nk) > 0.0 && glm::dot(p - pk, (n + nk) * 0.5) >= -0.05 * radius;
    if (std::abs(w * accuracy - 1.0) > 1e-4)
      EXPECT_EQ(record_usable(wf, float(accuracy), vec3(p), vec3(n), vec3(pk), vec3(nk), float(radius)), usable);
  }
  // Limits that follow from the weight cap: a record's own pixel (the capped weight) passes at the smallest accuracy.
  EXPECT_GT(MAX_RECORD_WEIGHT * MIN_ACCURACY, 1.0f);
  EXPECT_FLOAT_EQ(fixed_point_irradiance_scale(2.0f, 0.5f), 7.0f);
  EXPECT_EQ(fixed_point_irradiance_scale(0.0f, 0.5f), 1.0f);
  EXPECT_EQ(fixed_point_irradiance_scale(NAN, 0.5f), 1.0f);
  EXPECT_TRUE(std::isfinite(fixed_point_irradiance_scale(3e38f, 100.0f)));
}

}  // namespace
}  // namespace rcsplat
