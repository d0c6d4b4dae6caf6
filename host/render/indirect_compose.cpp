// The cache methods' composition: glossy pixels' specular light, then each pixel's BRDF applied to the cached
// irradiance (kernels/glossy.cl, kernels/compose.cl).
#include <atomic>

#include "passes/compose_pass.h"
#include "passes/glossy_pass.h"
#include "render/indirect.h"
#include "util/parallel.h"

namespace rcsplat {

void compose_cached_indirect(IndirectFrame& f, const cl::Buffer& irradiance, const RadianceSplatPass* radiance_cached,
                             const cl::Buffer* records, uint32_t record_count) {
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  const GBufferView& gbuffer = f.gbuffer.view();
  BuildTimer builds(f.gpu, st.program_s);
  const FramePasses& passes = f.plan.passes;
  const bool sample_hsh = passes.glossy_samples_hsh;
  // The radiance records left the light guide's share of their light to the pixels (kernels/glossy.cl guide_share);
  // none where the guide's photons found no lit surface.
  const CacheSettings& cs = f.settings.cache;
  const std::vector<GuideCluster>* guide = frame_light_guide(f);
  const bool guide_share = passes.glossy_guide_share && guide && !guide->empty();
  GlossyPass* glossy = nullptr;
  if (passes.glossy)
    glossy = &f.passes.glossy.get(
        sample_hsh, [&] { return std::make_unique<GlossyPass>(f.gpu, f.device_scene, sample_hsh); });
  // The glossy samples read the records where they land (the bounces after a hit), by position.
  WorldRecordGridPass* record_grids = nullptr;
  if (passes.world_record_grid && records)
    record_grids = &f.passes.world_record_grid.get({}, [&] { return std::make_unique<WorldRecordGridPass>(f.gpu); });
  ComposePass& compose = f.passes.compose.get(passes.radiance_records, [&] {
    return std::make_unique<ComposePass>(f.gpu, f.device_scene, passes.radiance_records);
  });
  builds.stop();

  CausticMapPass* caustics = attach_caustic_map(f);
  if (caustics) {
    StageTimer timing(st.caustics.seconds, f.gpu);
    caustics->add_to(gbuffer, irradiance);
  }
  if (glossy) {
    {
      StageTimer timing(st.glossy.seconds);
      // The records' grid by position, built where they are.
      DeviceWorldRecordGrid grid;
      GlossyCacheReads reads;
      if (record_grids) {
        StageTimer grid_timing(st.glossy.record_grid_s);
        // The light the records leave to the caustic map, added at each record for the samples.
        const cl::Buffer& read = caustics ? caustics->lit_records(*records, record_count) : *records;
        grid = record_grids->build(read, record_count, cs.accuracy);
        reads.device = &grid;
        reads.caustics = caustics;
        st.glossy.reads_records = true;
        f.gpu.queue().finish();  // the grid's time is its own, not the glossy samples'
        grid_timing.stop();
      }
      const GlossyRunStats run = glossy->run(
          gbuffer, f.settings.glossy_samples, f.settings.seed, guide ? *guide : std::vector<GuideCluster>{},
          guide_share ? cs.theta_strata * cs.phi_strata : 0u, guide_share ? cs.guide_rays : 0u, f.settings.bounces,
          reads, {&f.direct.radiance(), &irradiance}, f.settings.glossy_adaptive);
      st.glossy.adaptive = f.settings.glossy_adaptive;
      st.glossy.rounds = std::max(st.glossy.rounds, run.rounds);
      const unsigned sub_pixels = unsigned(gbuffer.sub_pixel_side * gbuffer.sub_pixel_side);
      if (run.sampled_sub_pixels)
        st.glossy.mean_samples = double(GLOSSY_CHUNK_LOBE) * double(run.chunks) / double(run.sampled_sub_pixels) *
                                 double(sub_pixels);
      st.glossy.most_samples = GLOSSY_CHUNK_LOBE * run.most_chunks * sub_pixels;
      st.glossy.refined_pixels += run.refined_pixels;
    }
    st.glossy.samples = f.settings.glossy_samples;
    st.glossy.rays += f.layers.sum_alpha(gbuffer, glossy->radiance());
  }
  {
    StageTimer timing(st.irradiance.resolve_s);
    compose.run(gbuffer, irradiance, f.direct.radiance(), glossy ? &glossy->radiance() : nullptr,
                radiance_cached ? &radiance_cached->lobe_radiance() : nullptr, guide_share);
  }

  StageTimer timing(st.primary.layers_s);
  const size_t pixels = f.layers.pixel_count();
  if (!layers_stay_on_device(f.settings)) {
    img.indirect.resize(pixels * 3);
    f.layers.mean_rgba(compose.indirect(), LayerPass::rgb_into(img.indirect));
    if (glossy) {
      img.glossy.resize(pixels * 3);
      f.layers.mean_rgba(glossy->radiance(), LayerPass::rgb_into(img.glossy));
    }
  }
  f.layers.mean_rgba(compose.color(), LayerPass::rgb_into(img.color));
}

void fill_cache_layers(IndirectFrame& f, const cl::Buffer& irradiance, const cl::Buffer& records_per_pixel,
                       const cl::Buffer& record_at_pixel) {
  RenderedImage& img = f.image;
  StageTimer timing(img.stats.primary.layers_s);
  if (layers_stay_on_device(f.settings)) {
    img.stats.irradiance.uncovered_pixels += f.layers.count_uncovered(f.gbuffer.view(), irradiance);
    return;
  }
  const size_t pixels = f.layers.pixel_count();
  img.irradiance.resize(pixels * 3);
  img.coverage.resize(pixels);
  img.records_per_pixel.resize(pixels);
  img.record_positions.resize(pixels);
  f.layers.mean_rgba(irradiance, [&](size_t first, const float* piece, size_t count) {
    parallel_ranges(count, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) {
        const size_t i = first + k;
        for (size_t c = 0; c < 3; ++c) img.irradiance[3 * i + c] = piece[4 * k + c];
        img.coverage[i] = piece[4 * k + 3];
      }
    });
  });
  std::atomic<uint64_t> uncovered{0};
  f.layers.record_counts(f.gbuffer.view(), irradiance, records_per_pixel, record_at_pixel,
                         [&](size_t first, const float* piece, size_t count) {
                           parallel_ranges(count, [&](size_t begin, size_t end) {
                             uint64_t range_uncovered = 0;
                             for (size_t k = begin; k < end; ++k) {
                               img.records_per_pixel[first + k] = piece[4 * k];
                               img.record_positions[first + k] = piece[4 * k + 1];
                               range_uncovered += uint64_t(piece[4 * k + 2]);
                             }
                             uncovered += range_uncovered;
                           });
                         });
  img.stats.irradiance.uncovered_pixels += uncovered;
}

}  // namespace rcsplat
