// Radiance cache splatting (Gautron et al. 2005) as the paper's algorithm box: place records coarse to fine where no
// record reaches, compute each level's records as one batch, clamp radii against neighbours, splat, and finally
// normalise and compose.
#include "passes/record_pass.h"
#include "passes/splat_pass.h"
#include "render/device_record_index.h"
#include "render/indirect.h"
#include "render/placement.h"

namespace rcsplat {

void splat_indirect(IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  const GBufferView& gbuffer = f.gbuffer.view();
  const PhotonMapPass* photon_map = attach_photon_map(f);
  double program_before = f.gpu.program_seconds();
  RecordPass records(f.gpu, f.device_scene, largest_theta_strata(cs), false, photon_map);
  records.set_bounces(f.settings.bounces);
  DeviceRecordIndex index(f.gpu, gbuffer, cs);
  SplatPass splat(f.gpu);
  st.program_s += f.gpu.program_seconds() - program_before;
  attach_light_guide(f, records);

  uint32_t total = place_records(index, records, gbuffer, cs, f.settings.seed, st);
  {
    // One splat of every record with its final radius, at the frame's fixed-point scale.
    StageTimer timing(st.splat_s);
    splat.splat_all(gbuffer, records.records(), total, cs.accuracy);
  }
  {
    StageTimer timing(st.resolve_s);
    splat.resolve(gbuffer);
    if (cs.finest_spacing_pixels > 1)  // sub-pixels: placement stopped one output pixel apart
      st.filled_sub_pixels = splat.fill_uncovered(gbuffer, records.records(), index.record_at_pixel_buffer(),
                                                  int(std::ceil(cs.max_reach_pixels)));
  }
  std::unique_ptr<RadianceSplatPass> radiance = radiance_cached_lobes(f);
  compose_cached_indirect(f, splat.irradiance(), radiance.get());
  {
    StageTimer timing(st.layers_s);
    img.records = records.download(0, total);  // once per frame, for the summary and the tests
    count_clamped_radii(img.records, cs, st);
  }
  fill_cache_layers(f, splat.irradiance(), splat.records_per_pixel_buffer(), index.record_at_pixel_buffer());
}

}  // namespace rcsplat
