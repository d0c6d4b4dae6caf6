#include "passes/light_guide_pass.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/colour.h"
#include "util/error.h"

namespace rcsplat {
void LightGuidePass::build_ahead(GpuContext& gpu, const DeviceScene& scene) { gpu.build_ahead(kProgram, scene.defines()); }

std::vector<double> light_source_powers(const std::vector<PunctualLight>& lights,
                                        const std::vector<EmissiveTriangle>& emitters,
                                        const std::vector<float>& emitter_mean_luminance) {
  constexpr double pi = std::numbers::pi;
  std::vector<double> power;
  for (const PunctualLight& l : lights) {
    double intensity = std::max(luminance(l.intensity), 0.0);
    if (l.type == LIGHT_DIRECTIONAL) power.push_back(intensity * pi);
    else if (l.type == LIGHT_SPOT) {
      double cos_outer = std::clamp(-double(l.spot_offset) / double(l.spot_scale), -1.0, 1.0);
      power.push_back(intensity * 2.0 * pi * (1.0 - cos_outer));
    } else power.push_back(intensity * 4.0 * pi);
  }
  for (size_t i = 0; i < emitters.size(); ++i) {
    const EmissiveTriangle& e = emitters[i];
    // A textured emitter's power is its texture's mean; an untextured one's its radiance's luminance, in double.
    const double emitted = emitter_textured_triangle(e) >= 0 ? double(emitter_mean_luminance.at(i)) : luminance(e.radiance);
    power.push_back(std::max(emitted, 0.0) * pi * double(e.area) * (emitter_double_sided(e) ? 2.0 : 1.0));
  }
  for (double& p : power)
    if (!std::isfinite(p)) p = 0.0;
  return power;
}

LightGuidePass::LightGuidePass(GpuContext& gpu, const DeviceScene& scene, double sky_power)
    : gpu_(gpu),
      scene_(scene),
      kernel_(gpu.kernel(kProgram, "shoot_photons", scene.defines())),
      glass_targets_(gpu.upload(std::vector<cl_float4>(1, cl_float4{}), CL_MEM_READ_ONLY, "photons")) {
  std::vector<double> power = light_source_powers(scene.lights(), scene.emitters(), scene.emitter_mean_luminance());
  // The environment's peak, after the emitters (kernels/light_guide.cl): its photons enter through a unit disc.
  if (scene.environment_peak_power() > 0.0f) power.push_back(double(scene.environment_peak_power()) * std::numbers::pi);
  // The sky's smooth part last, for the bounce probe.
  sky_source_ = sky_power > 0.0 && std::isfinite(sky_power) && scene.environment_present();
  if (sky_source_) power.push_back(sky_power);
  double total = 0.0;
  for (double p : power) total += p;
  if (!(total > 0.0)) return;
  std::vector<cl_float> cdf;
  double running = 0.0;
  for (double p : power) cdf.push_back(cl_float((running += p) / total));
  cdf.back() = 1.0f;
  source_cdf_ = gpu_.upload(cdf, CL_MEM_READ_ONLY, "light guide");
  source_count_ = unsigned(cdf.size());
}

std::vector<PhotonHit> LightGuidePass::shoot(unsigned photon_count, unsigned seed, unsigned landings,
                                             unsigned first_stored, PhotonKeep keep) {
  size_t slots = 0;
  const cl::Buffer photons = shoot_on_device(photon_count, seed, landings, first_stored, keep, slots);
  return gpu_.download<PhotonHit>(photons, slots);
}

void LightGuidePass::aim_at(const std::vector<cl_float4>& spheres) {
  if (spheres.empty()) return;
  glass_targets_ = gpu_.upload(spheres, CL_MEM_READ_ONLY, "photons");
  glass_target_count_ = unsigned(spheres.size());
}

cl::Buffer LightGuidePass::shoot_on_device(unsigned photon_count, unsigned seed, unsigned landings,
                                           unsigned first_stored, PhotonKeep keep, size_t& slots) {
  slots = 0;
  if (!source_count_ || !photon_count || first_stored >= landings) return {};
  slots = size_t(photon_count) * (landings - first_stored);
  cl::Buffer photons = gpu_.buffer(CL_MEM_READ_WRITE, slots * sizeof(PhotonHit), "photons");
  PhotonParams params{};
  params.photon_count = photon_count;
  params.source_count = source_count_;
  params.seed = seed;
  params.landings = landings;
  params.first_stored = first_stored;
  params.sky_source = sky_source_ ? 1u : 0u;
  params.caustic = keep == PhotonKeep::after_sharp_lobe ? 1u : 0u;
  if (keep == PhotonKeep::through_glass_volume && !glass_target_count_)
    throw Error("glass caustic photons: no glass volume to aim at");
  params.glass_caustics = keep == PhotonKeep::through_glass_volume ? glass_target_count_ : 0u;
  scene_.bind(kernel_);
  kernel_.set_buffer<cl_float>("source_cdf", source_cdf_)
      .set_buffer<cl_float4>("glass_targets", glass_targets_)
      .set("params", params)
      .set_buffer<PhotonHit>("photons", photons);
  kernel_.launch(photon_count, gpu_.groups().traversal);
  return photons;
}

}  // namespace rcsplat
