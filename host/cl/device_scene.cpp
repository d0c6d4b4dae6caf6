#include "cl/device_scene.h"

#include <algorithm>
#include <numbers>

#include "scene/scene_plan.h"
#include "util/error.h"

namespace rcsplat {

DeviceScene::DeviceScene(GpuContext& gpu, const Scene& scene, const Bvh8& bvh,
                         const std::set<std::string>& forced_switches,
                         const SceneFrame& frame)
    : bvh_(gpu, bvh), frame_(frame) {
  PackedScene p = pack_scene(scene, frame);
  triangles_ = gpu.upload(p.triangles, CL_MEM_READ_ONLY, "triangles");
  // One float4 a vertex with normal maps; else one unread float4, for the argument.
  tangents_ = gpu.upload(p.tangents.empty() ? std::vector<float>(4, 0.0f) : p.tangents, CL_MEM_READ_ONLY, "triangles");
  materials_ = gpu.upload(p.materials, CL_MEM_READ_ONLY, "materials");
  materials_host_ = p.materials;
  textures_ = gpu.upload(p.textures, CL_MEM_READ_ONLY, "textures");
  texels_ = gpu.upload(p.texels, CL_MEM_READ_ONLY, "textures");
  upload_lights(gpu, p);
  environment_ = gpu.upload(p.environment.texels, CL_MEM_READ_ONLY, "environment");  // float4 per texel
  environment_cdf_ = gpu.upload(p.environment.cdf, CL_MEM_READ_ONLY, "environment");
  counts_.environment_width = p.environment.width;
  counts_.environment_height = p.environment.height;
  counts_.environment_rotation[0] = p.environment.rotation[0];
  counts_.environment_rotation[1] = p.environment.rotation[1];
  counts_.environment_peak_power = p.environment.peak_power;
  environment_smooth_power_ = p.environment.mean_luminance * 4.0 * std::numbers::pi * (1.0 - p.environment.peak_fraction);

  for (const Material& m : p.materials) ++lobe_counts_[size_t(m.lobe)];
  for (const auto& [name, value] : scene_switches(p, scene.has_vertex_colors(), forced_switches))
    defines_[name] = value;
  bvh_.add_defines(defines_);
  if (has_glass_caustics()) set_glass_caustics(gpu, {}, {}, {});
}

void DeviceScene::set_glass_caustics(GpuContext& gpu, const std::vector<PhotonHit>& photons,
                                     const std::vector<cl_uint>& buckets, std::vector<CausticMapLevel> levels) {
  // A kernel reads no photon of an empty level (photon_count 0), but the buffers must be bound.
  if (levels.size() > GLASS_CAUSTIC_LEVELS) throw Error("glass caustic map: more levels than the kernels read");
  levels.resize(GLASS_CAUSTIC_LEVELS, CausticMapLevel{});
  glass_caustic_photons_ =
      gpu.upload(photons.empty() ? std::vector<PhotonHit>(1) : photons, CL_MEM_READ_ONLY, "glass caustic map");
  glass_caustic_buckets_ = gpu.upload(buckets.empty() ? std::vector<cl_uint>(2, 0u) : buckets, CL_MEM_READ_ONLY,
                                      "glass caustic map buckets");
  glass_caustic_levels_ = gpu.upload(levels, CL_MEM_READ_ONLY, "glass caustic map levels");
}

void DeviceScene::move(GpuContext& gpu, const Scene& scene, const Bvh8* bvh, const MovingBvh::Changed& rows,
                       const std::vector<TriangleRange>& moved_triangles) {
  if (bvh) bvh_.write_rows(gpu, *bvh, rows);
  // Only the moved triangles are packed again: a move costs its part's size, not the scene's.
  bool emitters_moved = false;
  for (const TriangleRange& r : moved_triangles) {
    if (!r.count) continue;
    std::vector<TriangleShading> shading(r.count);
    // Emitters are listed in triangle order.
    auto e = std::lower_bound(emitter_triangle_.begin(), emitter_triangle_.end(), uint32_t(r.first));
    for (size_t i = 0; i < r.count; ++i) {
      const size_t t = r.first + i;
      float twice_area = 0.0f;
      shading[i] = pack_triangle(scene, frame_, t, &twice_area);
      if (e == emitter_triangle_.end() || *e != t) continue;
      const size_t k = size_t(e - emitter_triangle_.begin());
      EmissiveTriangle& emitter = emitters_host_[k];
      shading[i].emitter = int(k);
      place_emitter(shading[i], twice_area, emitter);
      const double sides = (emitter.sides_and_texture & 1) ? 2.0 : 1.0;
      emitter_power_[k] = emitter_emitted_[k] * emitter.area * sides;
      emitter_area_[k] = double(emitter.area) * sides;
      emitters_moved = true;
      ++e;
    }
    gpu.queue().enqueueWriteBuffer(triangles_, CL_TRUE, r.first * sizeof(TriangleShading),
                                   r.count * sizeof(TriangleShading), shading.data());
    if (scene.tangents.size() == 3 * scene.triangle_count()) {  // 4 floats a vertex, 3 vertices a triangle
      std::vector<float> tangents;
      tangents.reserve(r.count * 12);
      for (size_t v = r.first * 3; v < (r.first + r.count) * 3; ++v) {
        const glm::vec4& t = scene.tangents[v];
        tangents.insert(tangents.end(), {t.x, t.y, t.z, t.w});
      }
      gpu.queue().enqueueWriteBuffer(tangents_, CL_TRUE, r.first * 12 * sizeof(float), tangents.size() * sizeof(float),
                                     tangents.data());
    }
  }
  // An emitter's place in the power-proportional table may change (its area, under a scale); lights are few.
  if (emitters_moved) {
    select_emitters(emitters_host_, emitter_power_, emitter_area_);
    emitters_ = gpu.upload(emitters_host_, CL_MEM_READ_ONLY, "lights");
  }
  lights_host_ = pack_lights(scene, frame_);
  lights_ = gpu.upload(lights_host_, CL_MEM_READ_ONLY, "lights");
}

void DeviceScene::upload_lights(GpuContext& gpu, const PackedScene& p) {
  emitter_triangle_ = p.emitter_triangle;
  emitter_emitted_ = p.emitter_emitted;
  emitter_power_ = p.emitter_power;
  emitter_area_ = p.emitter_area;
  lights_ = gpu.upload(p.lights, CL_MEM_READ_ONLY, "lights");
  emitters_ = gpu.upload(p.emitters, CL_MEM_READ_ONLY, "lights");
  lights_host_ = p.lights;
  emitters_host_ = p.emitters;
  emitter_mean_luminance_ = p.emitter_mean_luminance;
  counts_.light_count = cl_uint(p.lights.size());
  counts_.emitter_count = cl_uint(p.emitters.size());
}

void DeviceScene::bind(NamedKernel& kernel) const {
  kernel.set_buffer<cl_float8>("nodes", bvh_.nodes())
      .set_buffer<cl_float8>("blocks", bvh_.blocks())
      .set_buffer<TriangleShading>("triangles", triangles_)
      .set_buffer<cl_float4>("tangents", tangents_)
      .set_buffer<Material>("materials", materials_)
      .set_buffer<TextureInfo>("textures", textures_)
      .set_buffer<cl_uint>("texels", texels_)
      .set_buffer<PunctualLight>("lights", lights_)
      .set_buffer<EmissiveTriangle>("emitters", emitters_)
      .set_buffer<cl_float4>("environment", environment_)
      .set_buffer<cl_float>("environment_cdf", environment_cdf_)
      .set("scene_counts", counts_);
  if (has_glass_caustics())
    kernel.set_buffer<PhotonHit>("glass_caustic_photons", glass_caustic_photons_)
        .set_buffer<cl_uint>("glass_caustic_buckets", glass_caustic_buckets_)
        .set_buffer<CausticMapLevel>("glass_caustic_levels", glass_caustic_levels_);
}

std::map<std::string, std::string> scene_plan_switches(const ScenePlan& plan, int bvh_depth) {
  std::map<std::string, std::string> switches = plan.switches;
  switches["BVH_STACK_SIZE"] = bvh_stack_switch(Bvh8::stack_size_for_depth(bvh_depth));
  return switches;
}

}  // namespace rcsplat
