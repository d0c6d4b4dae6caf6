// The light guide for a frame's records: photons from the lights, clustered into the brightest directly lit places.
#include "cache/light_guide.h"
#include "passes/light_guide_pass.h"
#include "render/indirect.h"
#include "render/timing.h"

namespace rcsplat {

void attach_light_guide(IndirectFrame& f, RecordPass& records) {
  const CacheSettings& cs = f.settings.cache;
  RenderStats& st = f.image.stats;
  if (!cs.guide_rays || !cs.guide_photons) return;
  if (f.light_guide) {
    records.set_light_guide(*f.light_guide, cs.guide_rays);
    return;
  }
  auto t = Clock::now();
  double program_before = f.gpu.program_seconds();
  LightGuidePass photons(f.gpu, f.device_scene);
  double program_s = f.gpu.program_seconds() - program_before;
  st.program_s += program_s;
  // Its own seed stream: the photons must not correlate with the records' hemispheres.
  std::vector<PhotonHit> hits = photons.shoot(cs.guide_photons, f.settings.seed ^ 0x6c677569u);
  std::vector<GuideCluster> clusters = cluster_photons(hits, GUIDE_MAX_CLUSTERS);
  records.set_light_guide(clusters, cs.guide_rays);
  f.light_guide = std::move(clusters);
  st.guide_photons = hits.size();
  st.guide_clusters = unsigned(f.light_guide->size());
  st.guide_s = seconds_since(t) - program_s;
}

}  // namespace rcsplat
