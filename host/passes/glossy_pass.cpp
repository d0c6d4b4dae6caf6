#include "passes/glossy_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "util/error.h"

namespace rcsplat {

GlossyPass::GlossyPass(GpuContext& gpu, const DeviceScene& scene, bool sample_radiance_cacheable)
    : gpu_(gpu),
      scene_(scene),
      kernel_(gpu.kernel("glossy.cl", "glossy_indirect", scene.defines_with("SAMPLE_HSH_LOBES", sample_radiance_cacheable))) {}

void GlossyPass::run(const GBufferView& gbuffer, unsigned samples, unsigned seed, const std::vector<GuideCluster>& guide,
                     unsigned record_strata, unsigned record_guide_rays, unsigned bounces) {
  if (gbuffer.pixel_count() != pixels_ || !radiance_()) {
    pixels_ = gbuffer.pixel_count();
    radiance_ = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(pixels_, 1) * 4 * sizeof(float), "glossy radiance");
  }
  if (guide.size() > GUIDE_MAX_CLUSTERS)
    throw Error("glossy: a light guide of more than " + std::to_string(GUIDE_MAX_CLUSTERS) + " clusters");
  GlossyParams params{};
  params.sample_count = samples;
  params.grid_side = unsigned(std::sqrt(double(samples)));
  params.seed = seed;
  params.guide_clusters = cl_uint(guide.size());
  params.bounces = bounces;
  if (record_strata && record_guide_rays && !guide.empty()) {
    params.record_strata = record_strata;
    params.record_guide_rays = record_guide_rays;
    params.guide_share_samples = std::max(1u, samples);
  }
  // An unused one-cluster buffer when there is no guide: the kernel reads none.
  gpu_.upload_into(guide_, guide_capacity_, guide.empty() ? std::vector<GuideCluster>(1, GuideCluster{}) : guide,
                   CL_MEM_READ_ONLY, "light guide");
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set("params", params)
      .set_buffer<GuideCluster>("guide", guide_)
      .set_buffer<cl_float4>("glossy_out", radiance_);
  kernel_.launch(pixels_, gpu_.groups().traversal);
  gpu_.queue().finish();
}

std::vector<float> GlossyPass::download_rgba() { return gpu_.download<float>(radiance_, pixels_ * 4); }

}  // namespace rcsplat
