// The photon map for a frame's records (--bounce-method photons): shot once, shared by the irradiance and radiance
// records, and kept by the Renderer for later frames with the same seed, bounces and photon settings.
#include <algorithm>

#include <glm/glm.hpp>

#include "passes/light_guide_pass.h"
#include "passes/photon_landings_pass.h"
#include "passes/photon_map_pass.h"
#include "render/indirect.h"
#include "kernels/counter_random.h"
#include "render/timing.h"

namespace rcsplat {
namespace {

// One photon in this many carries a radiance estimate for the lookups: Christensen (1999) kept a quarter; the lookup
// searches this many times fewer photons, each estimate still sums all of them.
constexpr unsigned kPhotonLookupStride = 8;

}  // namespace

double device_surface_area(const Scene& scene, const SceneFrame& frame) {
  double area = 0.0;
  for (size_t i = 0; i + 2 < scene.positions.size(); i += 3) {
    glm::dvec3 a(scene.positions[i]), b(scene.positions[i + 1]), c(scene.positions[i + 2]);
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area / (frame.scale * frame.scale);
}

const PhotonMapPass* attach_photon_map(IndirectFrame& f) {
  if (!f.plan.passes.photon_map) return nullptr;
  RenderStats& st = f.image.stats;
  ViewIndependentLight& light = f.light;
  const ViewIndependentLight::PhotonKey key{f.settings.seed, f.settings.bounces, f.settings.photon_paths,
                                            f.settings.photon_neighbours};
  KeptLight* stored = f.kept_light;
  // A map built by a frame that kept nothing is shot again (the same photons, so the same map) when a frame keeps
  // records, so that a cache file written after it holds its photons.
  const bool unstored = stored && !stored->has_photon_map;
  if (!light.photon_map || light.photon_key != key || unstored) {
    const bool had_map = light.photon_map != nullptr;
    light.photon_map.reset();
    StageTimer timing(st.photon_map.seconds, f.gpu, st.program_s);
    st.photon_map.made = true;
    const SceneFrame& frame = f.device_scene.frame();
    const bool rounds = f.settings.photon_paths == 0;
    // A path lands up to bounces - 1 times after a reflection: a round of kPhotonMapPhotons / (bounces - 1) paths
    // fills a closed scene's map.
    const unsigned per_round =
        rounds ? std::max(kPhotonMapPhotons / (f.settings.bounces - 1), 1024u) : f.settings.photon_paths;
    // The photons stay on the device from their shooting to the grids (passes/photon_landings_pass.h).
    PhotonLandingsPass kept(f.gpu);
    uint64_t paths = 0;
    // A cache file's photons (sequence/cache_file.h) for a Renderer that has built no map yet: the same photons, so the
    // same map on the same device.
    if (stored && stored->has_photon_map && !had_map) {
      kept.load(stored->photons);
      paths = stored->photon_paths;
    } else {
      LightGuidePass lights(f.gpu, f.device_scene);
      // Within a tenth of the goal is enough: a closed scene keeps nearly every photon, and another round would double
      // them.
      for (unsigned round = 0; round < (rounds ? kPhotonRounds : 1u) && kept.kept() < kPhotonMapPhotons / 10 * 9;
           ++round) {
        StageTimer shoot(st.photon_map.shoot_s, f.gpu);
        // Its own seed stream, as the light guide's: the map must not correlate with the records' hemispheres. The
        // landings after the first reflection, the lit ones kept.
        size_t slots = 0;
        const cl::Buffer landings = lights.shoot_on_device(
            per_round, f.settings.seed ^ STREAM_PHOTON_MAP ^ hash_u32(round), f.settings.bounces, 1, PhotonKeep::every_landing, slots);
        kept.append_lit(landings, uint32_t(slots));
        paths += per_round;
      }
      // Each round's photons carry the lights' whole power between them: R rounds, each 1 / R of it.
      kept.scale_flux(float(per_round) / float(paths));
      if (stored) {  // kept with the records for a cache file
        stored->has_photon_map = true;
        stored->photon_paths = paths;
        stored->photons = f.gpu.download<PhotonHit>(kept.photons(), kept.kept());
      }
    }
    StageTimer grids_timing(st.photon_map.grids_s, f.gpu);
    // The landings a path continued one bounce still needs: all but the last.
    const DevicePhotonGrids grids =
        sort_photon_grids(f.gpu, kept, device_surface_area(f.scene, frame), f.settings.photon_neighbours,
                          kPhotonLookupStride, frame.device_positions(f.scene), int(f.settings.bounces) - 1);
    f.gpu.queue().finish();  // the sort's time is the grids'
    grids_timing.stop();
    StageTimer estimate(st.photon_map.estimate_s, f.gpu);
    light.photon_map = std::make_unique<PhotonMapPass>(f.gpu, grids);
    light.photon_key = key;
    light.photon_paths = paths;
    light.photons = grids.all_grid.photon_count;
    light.photon_radius = frame.length_to_world(grids.all_grid.radius);
  }
  // How lookups read the map is the frame's to say: a kept map serves other --short-ray-paths and
  // --photon-min-support without being made again.
  light.photon_map->set_lookup(f.settings.short_ray_paths, f.settings.photon_min_support);
  st.photon_map.paths = light.photon_paths;
  st.photon_map.photons = light.photons;
  st.photon_map.radius = light.photon_radius;
  return light.photon_map.get();
}

}  // namespace rcsplat
