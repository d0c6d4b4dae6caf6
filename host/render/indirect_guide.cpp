// The light guide for a frame's records: photons from the lights, clustered into the brightest directly lit places.
// Built by the first frame that asks for it and kept by the Renderer while the seed and photon count stay the same.
// Clustered on the device where it has doubles (passes/guide_cluster_pass.h), else on the host: the same clusters.
#include "cache/light_guide.h"
#include "passes/guide_cluster_pass.h"
#include "passes/light_guide_pass.h"
#include "render/indirect.h"
#include "kernels/counter_random.h"
#include "render/timing.h"

namespace rcsplat {

const std::vector<GuideCluster>* frame_light_guide(const IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  const auto& guide = f.light.guide;
  if (!f.plan.passes.light_guide || !guide || guide->seed != f.settings.seed ||
      guide->photons != cs.guide_photons)
    return nullptr;
  return &guide->clusters;
}

void attach_light_guide(IndirectFrame& f, RecordPass& records) {
  const CacheSettings& cs = f.settings.cache;
  RenderStats& st = f.image.stats;
  if (!f.plan.passes.light_guide) return;
  KeptLight* stored = f.kept_light;
  if (frame_light_guide(f) && (!stored || stored->has_guide)) {
    // Built by an earlier frame with these settings (and kept with the records when this frame keeps them: otherwise
    // shot again below, the same photons, so that a cache file holds the guide).
  } else if (stored && stored->has_guide && !f.light.guide) {
    // A cache file's clusters, for a Renderer that has built no guide yet.
    f.light.guide = ViewIndependentLight::Guide{f.settings.seed, cs.guide_photons, stored->guide_clusters,
                                                stored->guide_hits};
  } else {
    StageTimer timing(st.guide.seconds, f.gpu, st.program_s);
    LightGuidePass photons(f.gpu, f.device_scene);
    // Its own seed stream: the photons must not correlate with the records' hemispheres.
    const unsigned seed = f.settings.seed ^ STREAM_LIGHT_GUIDE;
    if (GuideClusterPass::available(f.gpu)) {  // the photons stay on the device; the same clusters
      size_t slots = 0;
      const cl::Buffer hits = photons.shoot_on_device(cs.guide_photons, seed, 1, 0, PhotonKeep::every_landing, slots);
      std::vector<GuideCluster> clusters;
      if (slots) clusters = GuideClusterPass(f.gpu).cluster(hits, uint32_t(slots), GUIDE_MAX_CLUSTERS);
      f.light.guide = ViewIndependentLight::Guide{f.settings.seed, cs.guide_photons, std::move(clusters), slots};
    } else {
      std::vector<PhotonHit> hits = photons.shoot(cs.guide_photons, seed);
      f.light.guide = ViewIndependentLight::Guide{f.settings.seed, cs.guide_photons,
                                                  cluster_photons(hits, GUIDE_MAX_CLUSTERS), hits.size()};
    }
    if (stored) {
      stored->has_guide = true;
      stored->guide_hits = f.light.guide->hits;
      stored->guide_clusters = f.light.guide->clusters;
    }
  }
  records.set_light_guide(f.light.guide->clusters, cs.guide_rays);
  st.guide.photons = f.light.guide->hits;
  st.guide.clusters = unsigned(f.light.guide->clusters.size());
}

}  // namespace rcsplat
