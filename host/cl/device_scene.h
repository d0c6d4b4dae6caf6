// Everything about the scene that the ray-tracing kernels read, on the device: the BVH, per-triangle shading data,
// materials, textures, lights (kernels/scene_args.h SCENE_ARGS). Also the one place that decides the kernels'
// compile-time switches from the scene.
#pragma once
#include <map>
#include <array>
#include <set>
#include <string>
#include <vector>

#include "bvh/bvh8.h"
#include "bvh/moving_bvh.h"
#include "cl/device_bvh.h"
#include "cl/gpu_context.h"
#include "scene/packed_scene.h"
#include "scene/scene_plan.h"

namespace rcsplat {

class DeviceScene {
 public:
  // forced_switches: scene switches compiled on whether the scene needs them or not (scene/scene_plan.h; tests show
  // that doing so changes no bit of the image).
  // bvh and the uploaded positions and lights are in `frame`'s coordinates (render() uses SceneFrame::fitted).
  DeviceScene(GpuContext& gpu, const Scene& scene, const Bvh8& bvh, const std::set<std::string>& forced_switches = {},
              const SceneFrame& frame = {});

  // Sets a kernel's SCENE_ARGS.
  void bind(NamedKernel& kernel) const;

  // Parts of `scene` (the one given at construction, changed in place) moved (render/renderer.h Renderer::move):
  // writes the BVH's rewritten rows (bvh: the whole tree; null when no triangle moved), the moved triangles' shading
  // and tangents, and the lights and emitters again.
  void move(GpuContext& gpu, const Scene& scene, const Bvh8* bvh, const MovingBvh::Changed& rows,
            const std::vector<TriangleRange>& moved_triangles);

  // scene_switches (scene/scene_plan.h) and BVH_STACK_SIZE: a scene compiles only the code it needs.
  const KernelDefines& defines() const { return defines_; }
  // The scene's switches plus a pass's own (name -> "1" or "0").
  KernelDefines defines_with(const std::string& name, bool on) const {
    KernelDefines d = defines_;
    d[name] = on ? "1" : "0";
    return d;
  }
  // Materials by LOBE_* (index), from their factors.
  const std::array<unsigned, LOBE_KINDS>& lobe_counts() const { return lobe_counts_; }
  bool has_specular_brdf() const { return defines_.at("HAS_SPECULAR_BRDF") == "1"; }
  bool has_glass() const { return defines_.at("HAS_TRANSMISSION") == "1"; }
  bool has_layers() const { return defines_.at("HAS_LAYERS") == "1"; }
  // --light-through-glass caustics in a scene with a glass volume: SCENE_ARGS carry the glass caustic map.
  bool has_glass_caustics() const { return defines_.at("HAS_GLASS_CAUSTICS") == "1"; }
  // Sets the glass caustic map every kernel's SCENE_ARGS then carry (passes/glass_caustics_pass.h makes it): its
  // levels' photons sorted by bucket, their buckets' first photons, and the GLASS_CAUSTIC_LEVELS levels (fewer: the
  // rest empty). Until then the map is empty and reads 0.
  void set_glass_caustics(GpuContext& gpu, const std::vector<PhotonHit>& photons, const std::vector<cl_uint>& buckets,
                          std::vector<CausticMapLevel> levels);
  // Radiance caching runs (and its kernels compile) only for a scene with a LOBE_HSH material.
  bool has_radiance_cache() const { return lobe_counts_[LOBE_HSH] > 0; }
  const std::vector<Material>& materials() const { return materials_host_; }
  // The lights as uploaded (device frame): the light guide weighs them by power.
  const std::vector<PunctualLight>& lights() const { return lights_host_; }
  const std::vector<EmissiveTriangle>& emitters() const { return emitters_host_; }
  const cl::Buffer& triangles() const { return triangles_; }  // TriangleShading a triangle
  const std::vector<float>& emitter_mean_luminance() const { return emitter_mean_luminance_; }
  const SceneFrame& frame() const { return frame_; }
  // The environment's peak: the sum of its luminance times solid angle (0: none; kernels/environment.h).
  float environment_peak_power() const { return counts_.environment_peak_power; }
  // Its smooth part (what is gathered, not sampled): luminance times solid angle over the sphere (0: no environment).
  double environment_smooth_power() const { return environment_smooth_power_; }
  bool environment_present() const { return counts_.environment_width > 0; }

 private:
  // The punctual lights and emissive triangles, with their host copies and counts.
  void upload_lights(GpuContext& gpu, const PackedScene& p);

  DeviceBvh bvh_;
  cl::Buffer triangles_, tangents_, materials_, textures_, texels_, lights_, emitters_, environment_, environment_cdf_;
  SceneCounts counts_{};
  cl::Buffer glass_caustic_photons_, glass_caustic_buckets_, glass_caustic_levels_;
  double environment_smooth_power_ = 0.0;
  KernelDefines defines_;
  std::array<unsigned, LOBE_KINDS> lobe_counts_{};
  std::vector<Material> materials_host_;
  std::vector<PunctualLight> lights_host_;
  std::vector<EmissiveTriangle> emitters_host_;
  std::vector<float> emitter_mean_luminance_;
  // Each emitter's triangle (ascending), mean luminance, power and area as chosen (PackedScene): move's inputs.
  std::vector<uint32_t> emitter_triangle_;
  std::vector<double> emitter_emitted_, emitter_power_, emitter_area_;
  SceneFrame frame_;
};

// The kernel switches a scene compiles as `info` reports them: the scene plan's (scene/scene_plan.h) with the BVH's
// stack size for a tree of this depth; DeviceScene::defines() holds the same (tests/scene_plan_test.cpp).
std::map<std::string, std::string> scene_plan_switches(const ScenePlan& plan, int bvh_depth);

}  // namespace rcsplat
