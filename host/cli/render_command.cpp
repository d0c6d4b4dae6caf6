#include <cstdio>
#include <nlohmann/json.hpp>

#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "cli/commands.h"
#include "image/image_io.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {

int run_render(const RenderOptions& options) {
  if (options.outputs.empty()) throw Error("render: give at least one output with -o OUT.exr or -o OUT.png");
  for (const std::string& out : options.outputs) {
    if (!is_output_format(out)) throw Error(out + ": unknown output format (use .exr or .png)");
  }
  Scene scene = load_scene(options.scene_path);
  DeviceInfo device = select_device(options.device);
  log_info("device: " + device.name + " (" + device.platform_name + ")");
  GpuContext gpu(device);
  RenderedImage image = render_direct(gpu, scene, options.settings);
  for (const std::string& out : options.outputs) write_render(out, image, options.exposure);

  const RenderStats& s = image.stats;
  double kernel_s = s.gbuffer_s + s.direct_s;
  double mrays = kernel_s > 0 ? double(s.primary_rays + s.shadow_rays) / kernel_s * 1e-6 : 0.0;
  std::printf("scene        %s\n", scene.source.c_str());
  std::printf("device       %s\n", s.device.c_str());
  std::printf("image        %d x %d, %u light samples per pixel\n", image.width, image.height, s.light_samples);
  std::printf("triangles    %zu (BVH: %zu nodes, %zu triangle blocks, depth %d)\n", s.triangles, s.bvh_nodes,
              s.bvh_blocks, s.bvh_depth);
  std::printf("rays         %llu primary, %llu shadow\n", (unsigned long long)s.primary_rays,
              (unsigned long long)s.shadow_rays);
  std::printf("time         BVH build %.3f s, upload %.3f s, kernel build %.3f s\n", s.bvh_build_s, s.upload_s, s.program_s);
  std::printf("             G-buffer %.3f s, direct light %.3f s (%.2f Mrays/s), total %.3f s\n", s.gbuffer_s,
              s.direct_s, mrays, s.total_s);
  for (const std::string& out : options.outputs) std::printf("wrote        %s\n", out.c_str());

  if (!options.json_path.empty()) {
    nlohmann::json j = {
        {"scene", scene.source}, {"device", s.device}, {"width", image.width}, {"height", image.height},
        {"light_samples", s.light_samples}, {"triangles", s.triangles},
        {"bvh", {{"nodes", s.bvh_nodes}, {"blocks", s.bvh_blocks}, {"depth", s.bvh_depth}}},
        {"rays", {{"primary", s.primary_rays}, {"shadow", s.shadow_rays}}},
        {"seconds", {{"bvh_build", s.bvh_build_s}, {"upload", s.upload_s}, {"kernel_build", s.program_s},
                     {"gbuffer", s.gbuffer_s}, {"direct", s.direct_s}, {"total", s.total_s}}},
        {"mrays_per_second", mrays}, {"outputs", options.outputs}};
    write_text_file(options.json_path, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace rcsplat
