// A Renderer kept across frames (render/renderer.h): later frames are the same bits as fresh renders, pay no setup
// and make no buffer. Host-side state, so it runs under the sanitizers too (scripts/sanitize.sh), unlike the
// convergence tests of gi_test.cpp.
#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "lobed_cornell_box.h"
#include "pass_probe.h"
#include "test_support.h"

namespace rcsplat {
namespace {

bool same_bits(const RenderedImage& a, const RenderedImage& b) {
  return a.color == b.color && a.indirect == b.indirect && a.direct == b.direct && a.records.size() == b.records.size();
}

// A renderer made once renders many frames (render/renderer.h): each the same bits as a renderer made for it alone,
// whatever the frames before it (another camera, another seed: the photon map and the light guide it keeps must be
// rebuilt for a new seed and kept for a new camera), and only the first pays for the BVH, the upload and the probe.
// The scene has radiance-cached lobes, so the lobe table and the HSH order come from the renderer too.
TEST(Renderer, LaterFramesAreTheSameBitsAsFreshRendersAndPayNoSetup) {
  const Scene scene = test::cornell_box_with_lobes(0.6f, 0.5f);
  RenderSettings first;  // the library's defaults: bounces, their method, pixel samples and HSH order chosen
  first.width = first.height = 32;
  first.light_samples = 4;
  RenderSettings moved = first;
  moved.camera_overrides.eye = glm::vec3(0.2f, 1.0f, 3.2f);
  RenderSettings reseeded = moved;
  reseeded.seed = 7;

  Renderer renderer(test::gpu(), scene);
  const FramePlan plan = renderer.plan(first);
  EXPECT_GE(plan.settings.bounces, 2u) << "chosen from the scene";
  EXPECT_EQ(plan.settings.bounce_method, BounceMethod::photons);
  EXPECT_EQ(plan.settings.pixel_samples, 4u);
  EXPECT_EQ(plan.side, 2u);
  EXPECT_GE(plan.settings.hsh_order, 1u) << "chosen from the roughness";
  EXPECT_EQ(plan.frame_settings().cache.min_reach_pixels, 2.0f * first.cache.min_reach_pixels) << "reach in sub-pixels";

  const RenderedImage a = renderer.render(plan);
  const RenderedImage b = renderer.render(moved);
  const RenderedImage c = renderer.render(reseeded);
  const RenderedImage again = renderer.render(plan);
  EXPECT_GT(a.stats.scene.bvh_build_s + a.stats.scene.upload_s, 0.0);
  for (const RenderedImage* later : {&b, &c, &again}) {
    EXPECT_EQ(later->stats.scene.bvh_build_s, 0.0);
    EXPECT_EQ(later->stats.scene.upload_s, 0.0);
    EXPECT_EQ(later->stats.bounces.probe_s, 0.0);
    EXPECT_EQ(later->stats.bounces.count, a.stats.bounces.count);
  }
  EXPECT_EQ(b.stats.photon_map.seconds, 0.0) << "another camera keeps the photon map";
  EXPECT_GT(c.stats.photon_map.seconds, 0.0) << "another seed rebuilds it";
  EXPECT_TRUE(same_bits(a, again));  // a is what render() gives: a renderer's first frame
  EXPECT_TRUE(same_bits(b, render(test::gpu(), scene, moved)));
  EXPECT_TRUE(same_bits(c, render(test::gpu(), scene, reseeded)));
  EXPECT_FALSE(same_bits(a, b));
}

// A later frame of the same plan makes no device buffer: every pass, the method's included, keeps its buffers in the
// Renderer (render/indirect.h MethodPasses), the image layers' band of surfaces too. The scene has glossy and
// radiance-cached lobes, so every splat pass runs. (The octree method, the classic baseline, keeps its index on the
// host and uploads it each frame.)
TEST(Renderer, ALaterFrameMakesNoBuffer) {
  const Scene scene = test::cornell_box_with_lobes(0.6f, 0.5f);
  for (GiMethod gi : {GiMethod::splat, GiMethod::path}) {
    RenderSettings s;
    s.width = s.height = 24;
    s.light_samples = 4;
    s.gi = gi;
    s.path.samples = 4;
    Renderer renderer(test::gpu(), scene);
    const FramePlan plan = renderer.plan(s);
    renderer.render(plan);
    const size_t before = test::PassProbe::buffers_made(test::gpu());
    renderer.render(plan);
    EXPECT_EQ(test::PassProbe::buffers_made(test::gpu()) - before, 0u) << gi_method_name(gi);
  }
}

// Every method through one renderer, at one and four samples a pixel, the same bits as fresh renders. The plain
// Cornell box (its kernels are those most tests build; the lobes' state is the test above's).
TEST(Renderer, EveryMethodThroughOneRendererMatchesFreshRenders) {
  const Scene scene = make_cornell_box();
  Renderer renderer(test::gpu(), scene);
  for (GiMethod gi : {GiMethod::splat, GiMethod::octree, GiMethod::path, GiMethod::none})
    for (unsigned pixel_samples : {1u, 4u}) {
      RenderSettings s;
      s.width = s.height = 24;
      s.light_samples = 4;
      s.gi = gi;
      s.path.samples = 8;
      s.pixel_samples = pixel_samples;
      EXPECT_TRUE(same_bits(renderer.render(s), render(test::gpu(), scene, s)))
          << gi_method_name(gi) << ", " << pixel_samples << " pixel samples";
    }
}

}  // namespace
}  // namespace rcsplat
