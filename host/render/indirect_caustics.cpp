// The caustic map for a frame's pixels (cache methods, scenes with a sharp lobe): shot once, kept by the Renderer for
// later frames with the same seed and photon settings.
#include "kernels/counter_random.h"
#include "passes/caustic_map_pass.h"
#include "render/indirect.h"
#include "render/timing.h"

namespace rcsplat {

CausticMapPass* attach_caustic_map(IndirectFrame& f) {
  if (!f.plan.passes.caustic_map) return nullptr;
  RenderStats& st = f.image.stats;
  ViewIndependentLight& light = f.light;
  const ViewIndependentLight::CausticKey key{f.settings.seed, f.settings.caustic_photons, f.settings.photon_neighbours};
  KeptLight* stored = f.kept_light;  // a cache file's photons for a Renderer that has built no map yet
  // Shot again for a frame that keeps records when a frame that kept nothing built the map (attach_photon_map).
  if (!light.caustic_map || light.caustic_key != key || (stored && !stored->has_caustic_map)) {
    const bool had_map = light.caustic_map != nullptr;
    light.caustic_map.reset();
    StageTimer timing(st.caustics.seconds, f.gpu, st.program_s);
    const SceneFrame& frame = f.device_scene.frame();
    std::vector<PhotonHit> photons;
    if (stored && stored->has_caustic_map && !had_map) {
      photons = stored->caustic_photons;
    } else {
      // Its own seed stream: the map must not correlate with the photon map's, the guide's or the records'.
      photons = shoot_caustic_photons(f.gpu, f.device_scene, f.settings.caustic_photons,
                                      f.settings.seed ^ STREAM_CAUSTIC_MAP);
      if (stored) {
        stored->has_caustic_map = true;
        stored->caustic_photons = photons;
      }
    }
    const float start = photon_gather_radius(device_surface_area(f.scene, frame), photons.size(),
                                             f.settings.photon_neighbours);
    const float radius = crowded_gather_radius(photons, start, f.settings.photon_neighbours);
    light.caustic_map = std::make_unique<CausticMapPass>(f.gpu, photons, radius);
    light.caustic_key = key;
    light.caustic_photons = photons.size();
    light.caustic_radius = frame.length_to_world(radius);
  }
  st.caustics.paths = f.settings.caustic_photons;
  st.caustics.photons = light.caustic_photons;
  st.caustics.radius = light.caustic_radius;
  return light.caustic_map.get();
}

}  // namespace rcsplat
