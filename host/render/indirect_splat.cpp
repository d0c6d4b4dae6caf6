// Radiance cache splatting (Gautron et al. 2005) as the paper's algorithm box: place records coarse to fine where no
// record reaches, compute each level's records as one batch, clamp radii against neighbours, splat, and finally
// normalise and compose.
#include <cmath>

#include "passes/placement_pass.h"
#include "passes/record_pass.h"
#include "passes/splat_pass.h"
#include "render/indirect.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {

void check_cache_settings(const CacheSettings& c) {
  // A record must pass its own threshold: the capped weight at its own pixel, MAX_RECORD_WEIGHT = 1e3, must exceed 1/a.
  if (!(c.accuracy >= 0.01f) || !(c.accuracy <= 100.0f)) throw Error("--accuracy must be between 0.01 and 100");
  if (c.theta_strata < 1 || c.theta_strata > RecordPass::kMaxThetaStrata || c.phi_strata < 1 || c.phi_strata > 4096)
    throw Error("--hemisphere MxN: M must be 1.." + std::to_string(RecordPass::kMaxThetaStrata) + " and N 1..4096");
  if (c.fine_theta_strata > RecordPass::kMaxThetaStrata || c.fine_phi_strata > 4096 ||
      (c.fine_theta_strata == 0) != (c.fine_phi_strata == 0))
    throw Error("--fine-hemisphere MxN: M must be 1.." + std::to_string(RecordPass::kMaxThetaStrata) + " and N 1..4096");
  if (!(c.min_spacing > 0.0f) || !(c.max_spacing >= c.min_spacing) || !std::isfinite(c.max_spacing))
    throw Error("--spacing MIN,MAX: need 0 < MIN <= MAX, in pixels");
  if (c.coarsest_spacing < 1) throw Error("the coarsest placement spacing must be at least 1 pixel");
}

void count_clamped_radii(const std::vector<CacheRecord>& records, const CacheSettings& cs, RenderStats& st) {
  for (const CacheRecord& r : records) {
    float px = cs.accuracy * r.radius / r.pixel_size;  // the reach in pixels
    if (px <= cs.min_spacing * 1.0001f) ++st.records_at_min_radius;
    else if (px >= cs.max_spacing * 0.9999f) ++st.records_at_max_radius;
  }
}

int coarsest_placement_spacing(const CacheSettings& cs) {
  int coarsest = 1;
  while (coarsest * 2 <= cs.coarsest_spacing) coarsest *= 2;
  return coarsest;
}

void count_placed(RenderStats& st, int spacing, uint32_t records) {
  if (!st.levels.empty() && st.levels.back().spacing == spacing) st.levels.back().records += records;
  else st.levels.push_back({spacing, records});
}

HemisphereParams hemisphere_params(const CacheSettings& cs, unsigned seed, int spacing) {
  bool fine = spacing == 1 && cs.fine_theta_strata > 0;
  HemisphereParams hp{};
  hp.theta_strata = fine ? cs.fine_theta_strata : cs.theta_strata;
  hp.phi_strata = fine ? cs.fine_phi_strata : cs.phi_strata;
  hp.seed = seed;
  hp.min_spacing = cs.min_spacing / cs.accuracy;
  hp.max_spacing = cs.max_spacing / cs.accuracy;
  return hp;
}

void splat_indirect(IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  check_cache_settings(cs);
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  double program_before = f.gpu.program_seconds();
  RecordPass records(f.gpu, f.device_scene, std::max(cs.theta_strata, cs.fine_theta_strata));
  PlacementPass placement(f.gpu, f.gbuffer, img.width, img.height);
  SplatPass splat(f.gpu);
  st.program_s += f.gpu.program_seconds() - program_before;

  const float min_radius = hemisphere_params(cs, f.settings.seed, 1).min_spacing;  // in pixel footprints
  int coarsest = coarsest_placement_spacing(cs);
  int level_count = int(std::log2(coarsest)) + 1;
  Progress progress("irradiance cache", size_t(level_count));
  uint32_t total = 0;
  for (int spacing = coarsest, level = 0; spacing >= 1; spacing /= 2, ++level) {
    // At spacing 1 every candidate becomes a record and covers itself, but neighbour clamping can shrink an older
    // record enough to uncover a pixel. So more rounds cover those, clamping only their own new records (a
    // symmetric clamp there would uncover pixels again, cascading along corners for dozens of rounds).
    uint32_t unchanged = 0;  // in the extra rounds older records keep their radii: only new ones add coverage
    for (int round = 0; round < (spacing == 1 ? 5 : 1); ++round) {
      auto t = Clock::now();
      uint32_t count = placement.find_uncovered(records.records(), total, cs.accuracy, spacing, unchanged);
      st.placement_s += seconds_since(t);
      if (!count) break;
      t = Clock::now();
      records.compute(f.gbuffer.samples(), f.gbuffer.camera(), placement.candidates(), count, total,
                      hemisphere_params(cs, f.settings.seed, spacing));
      st.records_s += seconds_since(t);
      t = Clock::now();
      placement.mark(records.records(), total, count);
      total += count;
      placement.clamp_neighbours(records.records(), total, total - count, round == 0, min_radius);
      unchanged = round == 0 ? 0 : total - count;
      st.placement_s += seconds_since(t);
      count_placed(st, spacing, count);
    }
    progress.update(size_t(level + 1));
  }
  // One splat of every record with its final radius, at the frame's fixed-point scale.
  auto t_splat = Clock::now();
  splat.splat_all(f.gbuffer, records.records(), total, cs.accuracy);
  st.splat_s += seconds_since(t_splat);
  progress.finish();
  auto t = Clock::now();
  splat.resolve(f.gbuffer, f.direct.radiance());
  st.resolve_s = seconds_since(t);
  st.records = total;
  st.record_rays = records.rays_cast();
  img.records = records.download(total);  // once per frame, for the summary and the tests
  count_clamped_radii(img.records, cs, st);

  // Download the layers the EXR carries.
  size_t pixels = size_t(img.width) * size_t(img.height);
  std::vector<float> irr = splat.irradiance_rgbw(), ind = splat.indirect_rgba(), color = splat.color_rgba();
  std::vector<uint32_t> counts = splat.records_per_pixel();
  std::vector<int32_t> at_pixel = placement.record_at_pixel();
  img.indirect.resize(pixels * 3);
  img.irradiance.resize(pixels * 3);
  img.coverage.resize(pixels);
  img.records_per_pixel.resize(pixels);
  img.record_positions.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    for (size_t c = 0; c < 3; ++c) {
      img.irradiance[3 * i + c] = irr[4 * i + c];
      img.indirect[3 * i + c] = ind[4 * i + c];
      img.color[3 * i + c] = color[4 * i + c];
    }
    img.coverage[i] = irr[4 * i + 3];
    img.records_per_pixel[i] = float(counts[i]);
    img.record_positions[i] = at_pixel[i] >= 0 ? 1.0f : 0.0f;
    if (img.triangle[i] >= 0 && ind[4 * i + 3] == 0.0f) ++st.uncovered_pixels;
  }
}

}  // namespace rcsplat
