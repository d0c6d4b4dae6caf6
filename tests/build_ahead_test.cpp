// The programs a frame is planned to use are the programs it uses: Renderer::build_programs_ahead starts building
// them side by side when the plan is made, and a program missing from that list would build alone when its pass asks
// (a cold frame pays for it serially), while one listed in vain costs a build's time on a core.
#include <gtest/gtest.h>

#include <cstdlib>

#include "lobed_cornell_box.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "test_support.h"

namespace rcsplat {
namespace {

void expect_programs_built_ahead(const Scene& scene, const RenderSettings& request, const std::string& what) {
  SCOPED_TRACE(what);
  const std::unique_ptr<GpuContext> gpu = test::fresh_gpu();
  Renderer renderer(*gpu, scene);
  const FramePlan plan = renderer.plan(request);
  const std::set<std::string> asked_by_plan = gpu->programs_asked_for();  // the bounce probe's, the lobe table's
  renderer.render(plan);
  const std::set<std::string> asked = gpu->programs_asked_for();
  const std::set<std::string> ahead = gpu->programs_built_ahead();
  for (const std::string& program : asked)
    if (!asked_by_plan.count(program)) EXPECT_TRUE(ahead.count(program)) << "not built ahead: " << program;
  for (const std::string& program : ahead) EXPECT_TRUE(asked.count(program)) << "built ahead in vain: " << program;
}

RenderSettings small(GiMethod gi) {
  RenderSettings s;
  s.width = 48;
  s.height = 36;
  s.gi = gi;
  return s;
}

TEST(BuildAhead, TheCornellBoxsDefaultFrameUsesExactlyItsProgramsBuiltAhead) {
  expect_programs_built_ahead(make_cornell_box(), small(GiMethod::splat), "splat, defaults");
}

TEST(BuildAhead, RadianceCachingPhotonsAndCausticsUseExactlyTheProgramsBuiltAhead) {
  const Scene lobed = test::cornell_box_with_lobes(0.05f, 0.4f);  // a glossy floor that casts caustics, an HSH box
  RenderSettings s = small(GiMethod::splat);
  s.bounces = 3;
  s.bounce_method = BounceMethod::photons;
  s.caustic_photons = 20000;
  expect_programs_built_ahead(lobed, s, "splat, radiance cache, photon map, caustic map");
  s.gi = GiMethod::octree;
  expect_programs_built_ahead(lobed, s, "octree");
  s = small(GiMethod::splat);
  s.bounces = 2;
  s.bounce_method = BounceMethod::path;
  s.cache.guide_rays = 0;
  expect_programs_built_ahead(lobed, s, "splat, path bounces, no guide");
}

TEST(BuildAhead, PathTracingAndDirectLightOnlyBuildNoCachePrograms) {
  RenderSettings s = small(GiMethod::path);
  s.bounces = 1;
  expect_programs_built_ahead(make_cornell_box(), s, "path");
  s.gi = GiMethod::none;
  expect_programs_built_ahead(make_cornell_box(), s, "none");
}

// RCSPLAT_BUILD_AHEAD=0: a program built ahead waits for the pass that asks for it, and one never asked for is never
// built (not even when its context goes).
TEST(BuildAhead, DeferredBuildsRunOnlyWhenAskedFor) {
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
  EXPECT_TRUE(gpu->built_kernel_names().count("scan_blocks"));
  EXPECT_FALSE(gpu->built_kernel_names().count("splat_records"));
  gpu.reset();  // must not build splat.cl on the way out (nor hang)
}

}  // namespace
}  // namespace rcsplat
