// Which passes and maps a frame runs, decided once (Renderer::plan) from its settled settings and the scene's lobes.
// Building programs ahead (Renderer::build_programs_ahead), attaching the maps and the guide (indirect_photons.cpp,
// indirect_caustics.cpp, indirect_guide.cpp), the radiance records (indirect_radiance.cpp) and composition
// (indirect_compose.cpp) read this set; none of them decides it again. `info` prints it.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "cl/gpu_context.h"
#include "kernels/shared_types.h"
#include "render/settings.h"

namespace rcsplat {

struct FramePasses {
  bool records = false;           // irradiance records (the cache methods)
  bool device_placement = false;  // placement and splat on the device (splat); the octree places and interpolates on the host
  bool photon_map = false;        // the records read their later bounces from photons (--bounce-method photons, 2+ bounces)
  bool caustic_map = false;       // light -> sharp lobe -> pixel paths through photons (--caustic-photons, a LOBE_GLOSSY surface)
  bool light_guide = false;       // records' guided rays toward the brightest lit places (--guide-rays, --guide-photons)
  bool radiance_records = false;  // the LOBE_HSH pixels' lobes from radiance records (the splat, a LOBE_HSH material)
  bool glossy = false;            // the glossy pass: sharp lobes sampled per pixel (kernels/glossy.cl)
  bool glossy_samples_hsh = false;  // ... the LOBE_HSH pixels' lobes too (no radiance records for them)
  bool glossy_guide_share = false;  // ... the light guide's share the radiance records leave to the pixels
  bool world_record_grid = false;   // the glossy samples read the records where they land (--bounces 2+)
  bool path = false;                // path-traced indirect light
  RecordTrace record_trace = RecordTrace::fused;  // how record rays are traced (GroupSizes::record_trace)
};

// The one decision. frame: the plan's settings (bounces and method settled); lobes: materials per LOBE_* kind
// (DeviceScene::lobe_counts, scene/scene_plan.h); trace: the device's record trace shape.
FramePasses decide_frame_passes(const RenderSettings& frame, const std::array<unsigned, LOBE_KINDS>& lobes,
                                RecordTrace trace);

// The set as names in the order a frame runs them ("gbuffer", "direct", "photon_map", ...), for `info` and JSON.
std::vector<std::string> frame_pass_names(const FramePasses& passes);

}  // namespace rcsplat
