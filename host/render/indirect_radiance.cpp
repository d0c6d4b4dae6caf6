// Radiance caching of the LOBE_HSH pixels (Křivánek et al. 2005), splatted as Gautron et al. 2005 splat irradiance:
// the lobe table of the cached materials, then records placed by the same coarse-to-fine loop on those pixels alone
// at a stricter accuracy, each projecting its strata onto HSH, then one splat of w * L_o with each pixel's view.
#include <algorithm>

#include "kernels/counter_random.h"
#include "kernels/hsh.h"
#include "passes/brdf_table_pass.h"
#include "passes/hsh_record_pass.h"
#include "passes/record_pass.h"
#include "render/device_record_index.h"
#include "render/indirect.h"
#include "render/placement.h"
#include "util/error.h"

namespace rcsplat {
namespace {

constexpr int kTableAngles = 32;         // view angles of the lobe table, cos(theta_o) at bin centres
constexpr unsigned kTableSamples = 4096;  // stratified reflections per (material, angle)
constexpr double kOrderShare = 0.95;     // the automatic order holds this much of what order 10 holds

BrdfTable truncated(const BrdfTable& full, int order) {
  BrdfTable t;
  t.order = order;
  t.angle_count = full.angle_count;
  t.energy = full.energy;
  size_t rows = full.energy.size(), n2 = size_t(order) * size_t(order);
  t.lobe.resize(rows * 2 * n2);
  for (size_t row = 0; row < rows; ++row)
    for (int term = 0; term < 2; ++term)
      for (size_t k = 0; k < n2; ++k)
        t.lobe[(row * 2 + size_t(term)) * n2 + k] = full.coefficient(row / size_t(full.angle_count),
                                                                    int(row % size_t(full.angle_count)), term, int(k));
  return t;
}

}  // namespace

RadianceLobeTable radiance_lobe_table(GpuContext& gpu, const DeviceScene& device_scene, unsigned seed) {
  RadianceLobeTable t;
  std::vector<BrdfMaterial> cached;
  for (const Material& m : device_scene.materials()) {
    t.row_of_material.push_back(m.lobe == LOBE_HSH ? int(cached.size()) : -1);
    if (m.lobe != LOBE_HSH) continue;
    BrdfMaterial b{};
    for (int c = 0; c < 3; ++c) b.base_color[c] = m.base_color[c];
    b.metallic = m.metallic;
    b.roughness = m.roughness;
    b.specular = m.specular;
    cached.push_back(b);
    t.sharpest_roughness = std::min(t.sharpest_roughness, m.roughness);
  }
  t.materials = cached.size();
  t.full = BrdfTablePass(gpu).compute(cached, HSH_MAX_ORDER, kTableAngles, kTableSamples, seed);
  return t;
}

unsigned automatic_hsh_order(const RadianceLobeTable& table) {
  int order = 1;
  for (size_t m = 0; m < table.materials; ++m) {
    double best = table.full.worst_captured_energy(m, HSH_MAX_ORDER);
    int n = 1;
    while (n < HSH_MAX_ORDER && table.full.worst_captured_energy(m, n) < kOrderShare * best) ++n;
    order = std::max(order, n);
  }
  return unsigned(order);
}

float hsh_captured_energy(const RadianceLobeTable& table, unsigned order) {
  float captured = 1.0f;
  for (size_t m = 0; m < table.materials; ++m)
    captured = std::min(captured, float(table.full.worst_captured_energy(m, int(order))));
  return captured;
}

float radiance_accuracy(const RadianceLobeTable& table, float accuracy) {
  // Radiance caching's stricter accuracy for glossier lobes: a times the sharpest cached roughness (the lobe's
  // angular width goes as roughness^2 = alpha; roughness itself keeps records from crowding), at least a / 2.
  return accuracy * std::max(0.5f, table.sharpest_roughness);
}

const RadianceSplatPass* radiance_cached_lobes(IndirectFrame& f) {
  if (!f.plan.passes.radiance_records) return nullptr;
  RenderStats& st = f.image.stats;
  const GBufferView& gbuffer = f.gbuffer.view();
  const RadianceLobeTable& lobes = *f.lobe_table;  // the plan settled the order from it

  // The order's table and passes; the lobe table itself counts where the plan computed it.
  StageTimer table_timing(st.radiance.lobe_table_s, f.gpu, st.program_s);
  const FrameRadiance radiance = f.plan.radiance();
  const unsigned order = radiance.order;
  st.radiance.order = order;
  st.radiance.captured_energy = radiance.captured_energy;

  CacheSettings cs = f.settings.cache;
  cs.accuracy = radiance.accuracy;
  st.radiance.accuracy = cs.accuracy;

  MethodPasses& passes = f.passes;
  RadianceSplatPass* splat = &passes.radiance_splat.get({order, f.plan.settings.seed}, [&] {
    return std::make_unique<RadianceSplatPass>(f.gpu, truncated(lobes.full, int(order)), lobes.row_of_material);
  });
  const GBufferView& cached = splat->radiance_cached_pixels(gbuffer);
  HshRecordPass& hsh =
      passes.hsh_records.get(order, [&] { return std::make_unique<HshRecordPass>(f.gpu, int(order)); });
  KeptRecords* kept_set = f.kept_radiance_records;  // a walkthrough's (render/kept_records.h), or null
  if (kept_set) kept_set->begin_frame(kept_records_key(f.settings));
  hsh.begin_frame(kept_set ? kept_set->largest_radiance() : 0.0f);
  DeviceRecordIndex& index =
      passes.radiance_index.get({}, [&] { return std::make_unique<DeviceRecordIndex>(f.gpu, cached, cs); });
  index.begin(cached, cs);
  table_timing.stop();
  RecordPass& records = frame_record_pass(f, cs, true);  // the irradiance records' photon map and guide

  // Radiance records kept from earlier frames, with their coefficients: fitted to this view and seated first, as the
  // irradiance records are (indirect_splat.cpp).
  uint32_t reused = 0;
  if (kept_set) {
    StageTimer timing(st.radiance.placement_s);
    std::vector<float> coefficients;
    const std::vector<CacheRecord> taken = kept_set->for_view(*f.camera, cs, &coefficients);
    reused = uint32_t(taken.size());
    records.load(taken);
    hsh.load(coefficients, reused);
    index.seat_kept(records, reused, cs);
    std::vector<float> kept_radii(taken.size());
    std::transform(taken.begin(), taken.end(), kept_radii.begin(), [](const CacheRecord& r) { return r.radius; });
    hsh.bound_fitted_gradients(records.records(), kept_radii);
  }

  const uint32_t total = place_records(
      index, records, cached, cs, f.settings.seed ^ STREAM_RADIANCE_RECORDS, st.radiance,
      [&](uint32_t first, uint32_t count, const HemisphereParams& hemisphere) {
        hsh.project(records.strata(), records.records(), first, count, hemisphere.theta_strata, hemisphere.phi_strata);
      },
      "radiance cache", reused);

  StageTimer splat_timing(st.radiance.splat_s);
  splat->splat_all(gbuffer, records.records(), hsh.coefficients(), total, cs.accuracy, hsh.largest_radiance());
  splat->resolve(gbuffer);
  if (cs.finest_spacing_pixels > 1)  // sub-pixels: placement stopped one output pixel apart
    st.radiance.filled_sub_pixels = splat->fill_uncovered(gbuffer, records.records(), hsh.coefficients(),
                                                          index.record_at_pixel_buffer(),
                                                          int(std::ceil(cs.max_reach_pixels)));
  splat_timing.stop();
  if (kept_set) {
    StageTimer timing(st.primary.layers_s);
    const std::vector<CacheRecord> placed = records.download(reused, total - reused);
    const std::vector<float> coefficients = hsh.download(reused, total - reused);
    kept_set->add(placed.data(), placed.size(), coefficients.data(), hsh.floats_per_record());
    kept_set->raise_largest_radiance(hsh.largest_radiance());
    st.kept_radiance_records = kept_set->stats();
  }
  return splat;
}

}  // namespace rcsplat
