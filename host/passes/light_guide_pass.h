// The light guide's photons (kernels/light_guide.cl): sends photons from the scene's lights, each light chosen in
// proportion to its power, and returns where they land and the flux those surfaces reflect. cache/light_guide.h turns
// them into the clusters the record pass aims rays at.
#pragma once
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "kernels/shared_types.h"

namespace rcsplat {

// Which landings a photon keeps (PhotonParams): every one; after_sharp_lobe, the caustic map's (landing 0 reflects
// only by a LOBE_GLOSSY lobe); through_glass_volume, the glass caustic map's (a landing whose way crossed a volume).
enum class PhotonKeep { every_landing, after_sharp_lobe, through_glass_volume };

class LightGuidePass {
 public:
  // sky_power > 0: the environment's smooth part is a source too, of that power (the bounce probe's; see PhotonParams).
  LightGuidePass(GpuContext& gpu, const DeviceScene& scene, double sky_power = 0.0);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);

  // photon_count photons (none when the scene has no light with power), each landing up to `landings` times (reflected
  // diffusely in between), landings first_stored .. landings - 1 returned: photon i's landing k at
  // [i * (landings - first_stored) + k - first_stored]; blocks until done. `keep`: which landings (PhotonKeep).
  std::vector<PhotonHit> shoot(unsigned photon_count, unsigned seed, unsigned landings = 1, unsigned first_stored = 0,
                               PhotonKeep keep = PhotonKeep::every_landing);
  // The glass volumes' bounding spheres (xyz centre, w radius; device frame) that PhotonKeep::through_glass_volume's
  // photons aim at (kernels/light_guide.cl); it needs at least one.
  void aim_at(const std::vector<cl_float4>& spheres);
  // The same landings left on the device, `slots` of them (0 and no buffer: none); does not block.
  cl::Buffer shoot_on_device(unsigned photon_count, unsigned seed, unsigned landings, unsigned first_stored,
                             PhotonKeep keep, size_t& slots);

 private:
  static constexpr const char* kProgram = "light_guide.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
  cl::Buffer source_cdf_, glass_targets_;
  unsigned glass_target_count_ = 0;
  unsigned source_count_ = 0;
  bool sky_source_ = false;
};

// Each source's emitted power (luminance, device units): punctual lights, then emissive triangles, as the kernel
// numbers them. A spot counts the whole solid angle of its outer cone, a directional light the unit disc the photons
// cross (the device frame fits the scene in the unit sphere).
std::vector<double> light_source_powers(const std::vector<PunctualLight>& lights,
                                        const std::vector<EmissiveTriangle>& emitters,
                                        const std::vector<float>& emitter_mean_luminance);

}  // namespace rcsplat
