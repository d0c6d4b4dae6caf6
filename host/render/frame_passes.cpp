#include "render/frame_passes.h"

namespace rcsplat {

FramePasses decide_frame_passes(const RenderSettings& s, const std::array<unsigned, LOBE_KINDS>& lobes,
                                RecordTrace trace) {
  FramePasses p;
  p.path = s.gi == GiMethod::path;
  p.records = s.gi == GiMethod::splat || s.gi == GiMethod::octree;
  if (!p.records) return p;
  p.device_placement = s.gi == GiMethod::splat;
  p.record_trace = trace;
  p.photon_map = s.bounce_method == BounceMethod::photons && s.bounces >= 2;
  // A material's lobe is already the sharpest its metallic-roughness texture can make (scene/packed_scene.cpp).
  p.caustic_map = s.caustic_photons > 0 && lobes[LOBE_GLOSSY] > 0;
  p.light_guide = s.cache.guide_rays > 0 && s.cache.guide_photons > 0;
  p.radiance_records = s.gi == GiMethod::splat && lobes[LOBE_HSH] > 0;
  p.glossy_samples_hsh = !p.radiance_records && lobes[LOBE_HSH] > 0;
  p.glossy_guide_share = p.radiance_records && p.light_guide;
  p.glossy = lobes[LOBE_GLOSSY] > 0 || p.glossy_samples_hsh || p.glossy_guide_share;
  p.world_record_grid = p.glossy && s.glossy_reads_records && s.bounces > 1;
  return p;
}

std::vector<std::string> frame_pass_names(const FramePasses& p) {
  std::vector<std::string> names = {"gbuffer", "direct"};
  auto add = [&](bool on, const char* name) {
    if (on) names.push_back(name);
  };
  add(p.photon_map, "photon_map");
  add(p.caustic_map, "caustic_map");
  add(p.light_guide, "light_guide");
  if (p.records)
    names.push_back(std::string("irradiance_records(") + record_trace_name(p.record_trace) + ")");
  add(p.device_placement, "splat");
  add(p.records && !p.device_placement, "octree");
  add(p.radiance_records, "radiance_records");
  add(p.world_record_grid, "world_record_grid");
  add(p.glossy, p.glossy_samples_hsh ? "glossy(with radiance-cached lobes)" : "glossy");
  add(p.records, "compose");
  add(p.path, "path");
  names.push_back("layers");
  return names;
}

}  // namespace rcsplat
