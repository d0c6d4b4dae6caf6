// The passes and maps a frame runs are decided once (render/frame_passes.h decide_frame_passes): the decision itself on
// every kind of scene and request, what a frame then runs (its statistics), and the programs it builds ahead (each
// pass's static build_ahead asks for the switches its constructor will, so a frame asks for exactly those).
#include <gtest/gtest.h>

#include <cstdlib>

#include "lobed_cornell_box.h"
#include "render/frame_passes.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "pass_probe.h"
#include "test_support.h"

namespace rcsplat {
namespace {

using Lobes = std::array<unsigned, LOBE_KINDS>;

// Materials per lobe kind: Lambertian, rough, radiance-cached (LOBE_HSH), glossy.
Lobes lobes(unsigned lambertian, unsigned rough, unsigned hsh, unsigned glossy) {
  Lobes l{};
  l[LOBE_NONE] = lambertian;
  l[LOBE_ROUGH] = rough;
  l[LOBE_HSH] = hsh;
  l[LOBE_GLOSSY] = glossy;
  return l;
}

// A request as the plan leaves it: bounces and their method settled.
RenderSettings settled(GiMethod gi, unsigned bounces, BounceMethod method) {
  RenderSettings s;
  s.width = 48;
  s.height = 36;
  s.gi = gi;
  s.bounces = bounces;
  s.bounce_method = method;
  return s;
}

TEST(FramePasses, ALambertianSceneRunsRecordsSplatAndGuideAndNothingGlossy) {
  const FramePasses p =
      decide_frame_passes(settled(GiMethod::splat, 3, BounceMethod::photons), lobes(5, 0, 0, 0), RecordTrace::fused);
  EXPECT_TRUE(p.records && p.device_placement && p.photon_map && p.light_guide);
  EXPECT_FALSE(p.caustic_map || p.radiance_records || p.glossy || p.world_record_grid || p.path);
  const FramePasses one =
      decide_frame_passes(settled(GiMethod::splat, 1, BounceMethod::photons), lobes(5, 0, 0, 0), RecordTrace::fused);
  EXPECT_FALSE(one.photon_map) << "one bounce has no later bounce to read from photons";
  const FramePasses path_bounces =
      decide_frame_passes(settled(GiMethod::splat, 3, BounceMethod::path), lobes(5, 0, 0, 0), RecordTrace::fused);
  EXPECT_FALSE(path_bounces.photon_map);
}

TEST(FramePasses, SharpLobesBringTheCausticMapTheGlossyPassAndItsRecordGrid) {
  RenderSettings s = settled(GiMethod::splat, 2, BounceMethod::path);
  FramePasses p = decide_frame_passes(s, lobes(3, 1, 0, 1), RecordTrace::wavefront);
  EXPECT_TRUE(p.caustic_map && p.glossy && p.world_record_grid);
  EXPECT_FALSE(p.glossy_samples_hsh || p.glossy_guide_share);
  EXPECT_EQ(p.record_trace, RecordTrace::wavefront);
  s.caustic_photons = 0;
  s.glossy_reads_records = false;
  p = decide_frame_passes(s, lobes(3, 1, 0, 1), RecordTrace::fused);
  EXPECT_FALSE(p.caustic_map || p.world_record_grid);
  EXPECT_TRUE(p.glossy);
  s = settled(GiMethod::splat, 1, BounceMethod::path);
  EXPECT_FALSE(decide_frame_passes(s, lobes(3, 1, 0, 1), RecordTrace::fused).world_record_grid)
      << "one bounce: a glossy sample's landing has no later bounce to read";
}

TEST(FramePasses, RadianceCachedLobesAreTheSplatsTheOctreeSamplesThem) {
  RenderSettings s = settled(GiMethod::splat, 2, BounceMethod::path);
  FramePasses p = decide_frame_passes(s, lobes(3, 0, 1, 0), RecordTrace::fused);
  EXPECT_TRUE(p.radiance_records && p.glossy_guide_share && p.glossy);
  EXPECT_FALSE(p.glossy_samples_hsh || p.caustic_map);
  s.cache.guide_rays = 0;
  p = decide_frame_passes(s, lobes(3, 0, 1, 0), RecordTrace::fused);
  EXPECT_FALSE(p.light_guide || p.glossy_guide_share || p.glossy) << "no guide: nothing left for the glossy pass";
  s = settled(GiMethod::octree, 2, BounceMethod::path);
  p = decide_frame_passes(s, lobes(3, 0, 1, 0), RecordTrace::fused);
  EXPECT_TRUE(p.records && p.glossy && p.glossy_samples_hsh);
  EXPECT_FALSE(p.device_placement || p.radiance_records || p.glossy_guide_share);
}

TEST(FramePasses, PathTracingAndDirectLightRunNoCachePass) {
  for (GiMethod gi : {GiMethod::path, GiMethod::none}) {
    const FramePasses p = decide_frame_passes(settled(gi, 3, BounceMethod::path), lobes(1, 1, 1, 1), RecordTrace::fused);
    EXPECT_EQ(p.path, gi == GiMethod::path);
    EXPECT_FALSE(p.records || p.photon_map || p.caustic_map || p.light_guide || p.radiance_records || p.glossy ||
                 p.world_record_grid);
    const std::vector<std::string> names = frame_pass_names(p);
    EXPECT_EQ(names.front(), "gbuffer");
    EXPECT_EQ(names.back(), "layers");
    EXPECT_EQ(names.size(), gi == GiMethod::path ? 4u : 3u);
  }
}

// What a frame runs is what its plan says: each planned map and pass leaves its statistics, and one not planned none;
// the programs it asks for are exactly those built ahead from the plan.
TEST(FramePasses, AFrameRunsItsPlannedPassesAndBuildsAheadExactlyTheirPrograms) {
  const Scene lobed = test::cornell_box_with_lobes(0.05f, 0.5f);  // a glossy floor that casts caustics, an HSH box
  RenderSettings s = settled(GiMethod::splat, 3, BounceMethod::photons);
  s.caustic_photons = 20000;
  const std::unique_ptr<GpuContext> gpu = test::fresh_gpu();
  Renderer renderer(*gpu, lobed);
  const FramePlan plan = renderer.plan(s);
  const FramePasses& p = plan.passes;
  ASSERT_TRUE(p.photon_map && p.caustic_map && p.light_guide && p.radiance_records && p.glossy &&
              p.world_record_grid)
      << ::testing::PrintToString(frame_pass_names(p));
  const std::set<std::string> asked_by_plan = test::PassProbe::programs_asked_for(*gpu);  // the bounce probe's, the lobe table's
  const RenderStats st = renderer.render(plan).stats;
  EXPECT_GT(st.photon_map.photons, 0u);
  EXPECT_GT(st.caustics.photons, 0u);
  EXPECT_GT(st.guide.photons, 0u);
  EXPECT_GT(st.radiance.records, 0u);
  EXPECT_GT(st.glossy.rays, 0u);
  EXPECT_TRUE(st.glossy.reads_records);
  EXPECT_EQ(st.path.rays, 0u);
  const std::set<std::string> asked = test::PassProbe::programs_asked_for(*gpu);
  const std::set<std::string> ahead = test::PassProbe::programs_built_ahead(*gpu);
  for (const std::string& program : asked)
    if (!asked_by_plan.count(program)) EXPECT_TRUE(ahead.count(program)) << "not built ahead: " << program;
  for (const std::string& program : ahead) EXPECT_TRUE(asked.count(program)) << "built ahead in vain: " << program;

  // The same renderer, a plan without the maps and the guide: none of them runs.
  RenderSettings plain = settled(GiMethod::splat, 2, BounceMethod::path);
  plain.caustic_photons = 0;
  plain.cache.guide_rays = 0;
  const FramePlan plain_plan = renderer.plan(plain);
  ASSERT_FALSE(plain_plan.passes.photon_map || plain_plan.passes.caustic_map || plain_plan.passes.light_guide);
  const RenderStats plain_st = renderer.render(plain_plan).stats;
  EXPECT_EQ(plain_st.photon_map.photons, 0u);
  EXPECT_EQ(plain_st.caustics.photons, 0u);
  EXPECT_EQ(plain_st.guide.photons, 0u);
}

// RCSPLAT_BUILD_AHEAD=0: a program built ahead waits for the pass that asks for it, and one never asked for is never
// built (not even when its context goes).
TEST(FramePasses, DeferredBuildsRunOnlyWhenAskedFor) {
  ::setenv("RCSPLAT_BUILD_AHEAD", "0", 1);
  std::unique_ptr<GpuContext> gpu = test::fresh_gpu();
  ::unsetenv("RCSPLAT_BUILD_AHEAD");
  gpu->build_ahead("scan.cl");
  gpu->build_ahead("splat.cl");
  EXPECT_TRUE(gpu->program_seconds_by_file().empty()) << "a deferred build ran before it was asked for";
  gpu->program("scan.cl");
  const std::map<std::string, double> built = gpu->program_seconds_by_file();
  EXPECT_TRUE(built.count("scan.cl"));
  EXPECT_FALSE(built.count("splat.cl"));
  EXPECT_TRUE(test::PassProbe::built_kernel_names(*gpu).count("scan_blocks"));
  EXPECT_FALSE(test::PassProbe::built_kernel_names(*gpu).count("splat_records"));
  gpu.reset();  // must not build splat.cl on the way out (nor hang)
}

}  // namespace
}  // namespace rcsplat
