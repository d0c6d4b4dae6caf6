// The records found by position in the world (issue 41 item 2, kernels/world_records.h): what a glossy sample reads
// where it lands must be what the splat gives a pixel there, for the same records.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "reference/world_record_grid.h"
#include "cache/world_record_grid.h"
#include "kernels/photon_grid.h"
#include "passes/glossy_pass.h"
#include "passes/world_record_grid_pass.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "scene/scene_frame.h"
#include "pass_probe.h"
#include "test_support.h"

namespace rcsplat {
namespace {

// The built-in Cornell box with a glossy tall box (a dielectric of roughness 0.2: LOBE_GLOSSY), so that a glossy
// pass exists to read the records.
Scene cornell_box_with_a_glossy_box() {
  Scene scene = make_cornell_box();
  SceneMaterial box = scene.materials[0];
  box.roughness = 0.2f;
  box.specular = 1.0f;
  scene.materials.push_back(box);
  for (size_t t = 22; t < 32; ++t) scene.triangle_material[t] = uint32_t(scene.materials.size() - 1);
  return scene;
}

// Every pixel the splat covers, read through the world grid at its G-buffer point: the same records reach it (the
// weight sum is positive exactly where the splat's is) and the irradiance agrees within the splat's fixed-point
// rounding (1e-5 relative, 1e-7 of the largest), as the octree's lookup does (tests/splat_test.cpp).
TEST(WorldRecords, ALookupByPositionGivesWhatTheSplatGivesThePixel) {
  // In its own device frame, so that the positions the image gives back are the device's bits.
  const Scene scene = SceneFrame::fitted(cornell_box_with_a_glossy_box()).device_scene(cornell_box_with_a_glossy_box());
  Renderer renderer(test::gpu(), scene);
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 96;
  settings.light_samples = 4;
  settings.cache.theta_strata = 8;
  settings.cache.phi_strata = 16;
  settings.caustic_photons = 0;  // the splat's irradiance alone, without the caustic map's added
  const RenderedImage img = renderer.render(settings);
  ASSERT_GT(img.records.size(), 100u);
  const WorldRecordGrid grid = build_world_record_grid(img.records, settings.cache.accuracy);
  std::vector<cl_float4> points, normals;
  std::vector<size_t> pixels;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    points.push_back({{img.position[3 * i], img.position[3 * i + 1], img.position[3 * i + 2], 0.0f}});
    normals.push_back({{img.normal[3 * i], img.normal[3 * i + 1], img.normal[3 * i + 2], 0.0f}});
    pixels.push_back(i);
  }
  GlossyPass glossy(test::gpu(), renderer.device_scene(), false);
  const std::vector<cl_float4> read = test::PassProbe::cached_irradiance_at(glossy, img.records, grid, points, normals);
  double scale = 0.0;
  for (float v : img.irradiance) scale = std::max(scale, double(v));
  size_t covered = 0;
  for (size_t k = 0; k < pixels.size(); ++k) {
    const size_t i = pixels[k];
    ASSERT_EQ(read[k].s[3] > 0.0f, img.coverage[i] > 0.0f) << "pixel " << i;
    covered += read[k].s[3] > 0.0f;
    for (int c = 0; c < 3; ++c) {
      const double expected = img.irradiance[3 * i + size_t(c)];
      ASSERT_NEAR(read[k].s[c], expected, 1e-5 * expected + 1e-7 * scale) << "pixel " << i << " channel " << c;
    }
  }
  EXPECT_GT(covered, pixels.size() * 9 / 10);
  std::printf("%zu of %zu pixels read both ways\n", covered, pixels.size());
}

// Each record is listed in every bucket of a cell its reach sphere meets, once: every point within a record's reach
// finds it in its own cell's bucket.
TEST(WorldRecords, EveryPointWithinAReachFindsItsRecordInItsCell) {
  std::vector<CacheRecord> records(300);
  uint32_t state = 7;
  auto next = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0f; };
  for (CacheRecord& r : records) {
    r = CacheRecord{};
    for (int a = 0; a < 3; ++a) r.position[a] = next();
    r.radius = 0.01f + 0.2f * next() * next();
  }
  const float accuracy = 0.3f;
  const WorldRecordGrid grid = build_world_record_grid(records, accuracy);
  ASSERT_EQ(grid.bucket_starts.size(), size_t(grid.params.bucket_count) + 1);
  const WorldRecordParams& g = grid.params;
  for (uint32_t k = 0; k < records.size(); ++k) {
    for (int s = 0; s < 50; ++s) {
      glm::vec3 d(next() - 0.5f, next() - 0.5f, next() - 0.5f);
      if (glm::length(d) == 0.0f) continue;
      const float reach = accuracy * records[k].radius;
      glm::vec3 p = glm::vec3(records[k].position[0], records[k].position[1], records[k].position[2]) +
                    glm::normalize(d) * (reach * 0.999f * next());
      const uint32_t bucket = photon_bucket(photon_cell(p.x, g.grid_origin[0], g.cell_size),
                                            photon_cell(p.y, g.grid_origin[1], g.cell_size),
                                            photon_cell(p.z, g.grid_origin[2], g.cell_size), g.bucket_count);
      const auto first = grid.record_lists.begin() + grid.bucket_starts[bucket],
                 last = grid.record_lists.begin() + grid.bucket_starts[bucket + 1];
      ASSERT_EQ(std::count(first, last, k), 1) << "record " << k;
    }
  }
}

// The grid the frames build on the device (passes/world_record_grid_pass.h) is the host's, bit for bit: parameters,
// bucket starts and lists, on random records that straddle the origin, include records the host leaves out (a NaN or
// zero radius, an infinite position), share diameters (the median's ties), crowd one spot (records listed twice in a
// bucket when two of their cells hash there), number more than one work-group, or are none at all. Planted once: the
// median one rank high (kept / 2 + 1) failed the cell size; the duplicate listings kept failed the lists.
TEST(WorldRecords, TheDeviceBuildsTheHostsGridBitForBit) {
  GpuContext& gpu = test::gpu();
  WorldRecordGridPass pass(gpu);
  std::mt19937 rng(43);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
  auto random_records = [&](size_t count, float spread, float radius_scale, bool ties, bool invalid) {
    std::vector<CacheRecord> records(count);
    for (size_t k = 0; k < count; ++k) {
      CacheRecord& r = records[k];
      r = CacheRecord{};
      for (int a = 0; a < 3; ++a) {
        r.position[a] = spread * u(rng);
        r.normal[a] = u(rng);
        r.irradiance[a] = 10.0f * unit(rng);
      }
      r.radius = ties ? radius_scale * float(1 + k % 4) : radius_scale * (0.05f + unit(rng) * unit(rng));
      if (invalid && k % 17 == 3) r.radius = std::nanf("");
      if (invalid && k % 17 == 5) r.radius = 0.0f;
      if (invalid && k % 17 == 7) r.position[1] = INFINITY;
    }
    return records;
  };
  struct Case {
    const char* name;
    std::vector<CacheRecord> records;
  };
  std::vector<Case> cases = {
      {"random", random_records(700, 1.0f, 0.3f, false, false)},
      {"with records left out", random_records(500, 3.0f, 1.0f, false, true)},
      {"tied diameters", random_records(257, 1.0f, 0.1f, true, false)},
      {"crowded", random_records(2000, 0.05f, 0.2f, false, false)},
      {"one record", random_records(1, 1.0f, 0.3f, false, false)},
      {"none listed", random_records(3, 1.0f, 0.3f, false, false)},
      {"no records", {}},
  };
  for (CacheRecord& r : cases[5].records) r.radius = -1.0f;
  for (const float accuracy : {0.3f, 0.7f})
    for (const Case& c : cases) {
      const WorldRecordGrid host = build_world_record_grid(c.records, accuracy);
      const cl::Buffer records = gpu.upload(c.records.empty() ? std::vector<CacheRecord>(1) : c.records);
      const WorldRecordGrid device =
          test::download_world_record_grid(gpu, pass.build(records, uint32_t(c.records.size()), accuracy));
      const std::string what = std::string(c.name) + " at a = " + std::to_string(accuracy);
      EXPECT_EQ(std::memcmp(&device.params, &host.params, sizeof(WorldRecordParams)), 0)
          << what << ": cell " << device.params.cell_size << " against " << host.params.cell_size << ", buckets "
          << device.params.bucket_count << " against " << host.params.bucket_count;
      EXPECT_EQ(device.bucket_starts, host.bucket_starts) << what;
      EXPECT_EQ(device.record_lists, host.record_lists) << what;
      if (c.records.size() > 1 && std::string(c.name) != "none listed")
        EXPECT_GT(host.record_lists.size(), c.records.size()) << what << ": records meet several cells";
    }
}

}  // namespace
}  // namespace rcsplat
