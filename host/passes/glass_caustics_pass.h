// The glass caustic map (kernels/glass_caustics.cl, docs/ALGORITHM.md section 12). With --light-through-glass caustics
// a glass volume stops shadow rays, and the light it passes reaches surfaces as photons instead: those whose way from
// a light to the first surface they land on crossed or reflected off a volume, so a glass ball focuses its light.
// Shot once for the scene (the light is the scene's, not a frame's), the map travels in every kernel's SCENE_ARGS
// (DeviceScene::set_glass_caustics): each bounce's direct light reads it, and this pass adds it to the pixels'.
#pragma once
#include <vector>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "scene/scene_frame.h"

namespace rcsplat {

// What a glass caustic map holds: photons kept of the paths shot, and its smallest and largest level's radius (device
// units).
struct GlassCausticMap {
  unsigned paths = 0;
  size_t photons = 0;
  float radius = 0.0f, largest_radius = 0.0f;
};

// The bounding spheres (xyz centre, w radius; `frame`'s device coordinates) of the scene's glass volumes, one a
// material (GLASS_CAUSTIC_LEVELS at most: the materials beyond share the last sphere), which the glass caustic map's
// photons aim at.
std::vector<cl_float4> glass_volume_spheres(const Scene& scene, const SceneFrame& frame);

// Each photon's level (CausticMapLevel): the smallest j whose radius smallest 2^j holds `neighbours` other photons
// about it (facing its way), the last level where none does.
std::vector<int> glass_caustic_levels(const std::vector<PhotonHit>& photons, float smallest, unsigned neighbours);

// Shoots settings.photons photon paths from the scene's lights toward the glass volumes' spheres `volumes` (a fixed
// seed stream: the same map for every frame and request) and sets them as the scene's glass caustic map in levels (glass_caustic_levels), the smallest radius the one
// where they crowd most, fitted from the radius that surface_area (device units) would give
// (passes/caustic_map_pass.h crowded_gather_radius). Blocks.
GlassCausticMap shoot_glass_caustics(GpuContext& gpu, DeviceScene& scene, double surface_area,
                                     const std::vector<cl_float4>& volumes, const GlassLight& settings);

class GlassCausticsPass {
 public:
  GlassCausticsPass(GpuContext& gpu, const DeviceScene& scene);
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);
  // Adds to direct (float4 a pixel: RGB, A shadow rays) what each pixel reflects toward the camera of the map's light
  // where it sees. Blocks.
  void add_to(const GBufferView& gbuffer, const cl::Buffer& direct);

 private:
  static constexpr const char* kProgram = "glass_caustics.cl";  // its kernels' file
  GpuContext& gpu_;
  const DeviceScene& scene_;
  NamedKernel kernel_;
};

}  // namespace rcsplat
