#include "passes/glass_caustics_pass.h"

#include "cache/photon_map.h"
#include "kernels/counter_random.h"
#include "passes/caustic_map_pass.h"
#include "passes/light_guide_pass.h"

namespace rcsplat {

GlassCausticMap shoot_glass_caustics(GpuContext& gpu, DeviceScene& scene, double surface_area,
                                     const GlassLight& settings) {
  GlassCausticMap map;
  map.paths = settings.photons;
  const std::vector<PhotonHit> photons = lit_landings(
      LightGuidePass(gpu, scene).shoot(settings.photons, STREAM_GLASS_CAUSTICS, 1, 0, PhotonKeep::through_glass_volume));
  const float start = photon_gather_radius(surface_area, photons.size(), settings.neighbours);
  map.radius = crowded_gather_radius(photons, start, settings.neighbours);
  map.photons = photons.size();
  const PhotonGrid grid = sort_into_grid(photons, map.radius);
  scene.set_glass_caustics(gpu, grid.photons, grid.bucket_starts, grid.params);
  return map;
}

void GlassCausticsPass::build_ahead(GpuContext& gpu, const DeviceScene& scene) {
  gpu.build_ahead(kProgram, scene.defines());
}

GlassCausticsPass::GlassCausticsPass(GpuContext& gpu, const DeviceScene& scene)
    : gpu_(gpu), scene_(scene), kernel_(gpu.kernel(kProgram, "add_glass_caustics", scene.defines())) {}

void GlassCausticsPass::add_to(const GBufferView& gbuffer, const cl::Buffer& direct) {
  scene_.bind(kernel_);
  gbuffer.bind(kernel_);
  kernel_.set_buffer<cl_float4>("direct", direct);
  kernel_.launch(gbuffer.pixel_count(), gpu_.groups().traversal);
  gpu_.queue().finish();
}

}  // namespace rcsplat
