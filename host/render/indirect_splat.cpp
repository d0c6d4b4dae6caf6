// Radiance cache splatting (Gautron et al. 2005) as the paper's algorithm box: place records coarse to fine where no
// record reaches, compute each level's records as one batch, clamp radii against neighbours, splat, and finally
// normalise and compose.
#include "passes/record_pass.h"
#include "passes/splat_pass.h"
#include "render/device_record_index.h"
#include "render/indirect.h"
#include "render/placement.h"

namespace rcsplat {

RecordPass& frame_record_pass(IndirectFrame& f, const CacheSettings& cache, bool radiance) {
  const PhotonMapPass* photon_map = attach_photon_map(f);
  BuildTimer builds(f.gpu, f.image.stats.program_s);
  // Radiance records keep the caustic paths in their rays: the map's irradiance reaches only the diffuse base and rough
  // lobes (kernels/caustic_map.cl).
  const bool caustics_apart = !radiance && f.plan.passes.caustic_map;
  if (caustics_apart) attach_caustic_map(f);
  const MethodPasses::RecordKey key{largest_theta_strata(cache), photon_map != nullptr, caustics_apart};
  RecordPass& records = (radiance ? f.passes.radiance_records : f.passes.irradiance_records).get(key, [&] {
    return std::make_unique<RecordPass>(f.gpu, f.device_scene, key.theta_strata, radiance, key.photon_gather,
                                        key.caustics_apart);
  });
  builds.stop();
  records.begin_frame(photon_map, f.settings.bounces);
  attach_light_guide(f, records);
  return records;
}

void splat_indirect(IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  const GBufferView& gbuffer = f.gbuffer.view();
  // Kept records computed with other settings go, and the photons kept with them (the maps are made again).
  if (f.kept_records && f.kept_records->begin_frame(kept_records_key(f.settings))) *f.kept_light = KeptLight{};
  RecordPass& records = frame_record_pass(f, cs, false);
  BuildTimer builds(f.gpu, st.program_s);
  DeviceRecordIndex& index =
      f.passes.irradiance_index.get({}, [&] { return std::make_unique<DeviceRecordIndex>(f.gpu, gbuffer, cs); });
  index.begin(gbuffer, cs);
  SplatPass& splat = f.passes.splat.get({}, [&] { return std::make_unique<SplatPass>(f.gpu); });
  builds.stop();

  // Records kept from earlier frames (a walkthrough): those this view may see, fitted to it and seated first.
  uint32_t kept = 0;
  if (f.kept_records) {
    StageTimer timing(st.irradiance.placement_s);
    const std::vector<CacheRecord> reused = f.kept_records->for_view(*f.camera, cs);
    kept = uint32_t(reused.size());
    records.load(reused);
    index.seat_kept(records, kept, cs);
  }
  uint32_t total = place_records(index, records, gbuffer, cs, f.settings.seed, st.irradiance, {}, "irradiance cache", kept);
  {
    // One splat of every record with its final radius, at the frame's fixed-point scale.
    StageTimer timing(st.irradiance.splat_s);
    splat.splat_all(gbuffer, records.records(), total, cs.accuracy);
  }
  {
    StageTimer timing(st.irradiance.resolve_s);
    splat.resolve(gbuffer);
    if (cs.finest_spacing_pixels > 1)  // sub-pixels: placement stopped one output pixel apart
      st.irradiance.filled_sub_pixels = splat.fill_uncovered(gbuffer, records.records(), index.record_at_pixel_buffer(),
                                                  int(std::ceil(cs.max_reach_pixels)));
  }
  {
    StageTimer timing(st.primary.layers_s);
    // The records stay on the device: a frame with every layer brings them back (tests read them); a colour-only
    // frame counts its clamped reaches there and brings back only those a walkthrough keeps.
    if (!layers_stay_on_device(f.settings)) {
      img.records = records.download(0, total);
      count_clamped_radii(img.records, cs, st.irradiance);
      if (f.kept_records) f.kept_records->add(img.records.data() + kept, total - kept);
    } else {
      const std::array<uint64_t, 2> clamped = f.layers.count_clamped_reaches(records.records(), total, cs);
      st.irradiance.at_min_radius += clamped[0];
      st.irradiance.at_max_radius += clamped[1];
      if (f.kept_records) {
        const std::vector<CacheRecord> added = records.download(kept, total - kept);
        f.kept_records->add(added.data(), added.size());
      }
    }
    if (f.kept_records) st.kept_records = f.kept_records->stats();
  }
  const RadianceSplatPass* radiance = radiance_cached_lobes(f);
  compose_cached_indirect(f, splat.irradiance(), radiance, &records.records(), total);
  fill_cache_layers(f, splat.irradiance(), splat.records_per_pixel_buffer(), index.record_at_pixel_buffer());
}

}  // namespace rcsplat
