// `rcsplat bench [SCENE] --devices all`: the same frame on every usable OpenCL device, as one table: kernel builds
// cold (no cache of rcsplat's or the driver's) and cached, a new process's first frame (BVH, upload, probe, programs
// from the on-disk cache), then the median time of each pass over the frames one renderer renders after it
// (render/renderer.h: no scene, BVH or program cost), records, the record pass's ray rate, peak device memory.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "cli/commands.h"
#include "util/atomic_file.h"
#include "render/renderer.h"
#include "util/byte_size.h"
#include "util/error.h"
#include "util/log.h"
#include "util/median.h"

namespace rcsplat {
namespace {

std::vector<DeviceInfo> chosen_devices(const std::string& selection) {
  if (selection.empty()) return {select_device("")};
  std::vector<DeviceInfo> chosen;
  if (selection == "all") {
    for (const DeviceInfo& d : list_devices())
      if (d.usable()) chosen.push_back(d);
    if (chosen.empty()) throw Error("bench --devices all: no usable OpenCL device (see `rcsplat devices`)");
    return chosen;
  }
  std::stringstream list(selection);
  for (std::string item; std::getline(list, item, ',');) chosen.push_back(select_device(item));
  return chosen;
}

}  // namespace

int run_bench_frames(const BenchOptions& o) {
  const Scene scene = load_scene(o.scene_path, 0, {}, {}, o.limits);  // empty: the built-in Cornell box, as for render
  const std::vector<DeviceInfo> devices = chosen_devices(o.devices.empty() ? o.device : o.devices);
  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  // bounces and pixel samples: 0, chosen from the scene, as `render` does.
  const auto nonce = std::chrono::steady_clock::now().time_since_epoch().count();

  nlohmann::json report = {{"scene", scene.source}, {"triangles", scene.triangle_count()}, {"width", o.width},
                           {"height", o.height}, {"repeats", o.repeats}, {"devices", nlohmann::json::array()}};
  std::printf("scene %s (%zu triangles), %d x %d, render defaults; per device a cold frame, a warm-up frame, a new "
              "renderer's first frame, then the median of the %d frames it renders next\n",
              scene.source.c_str(), scene.triangle_count(), o.width, o.height, o.repeats);
  std::printf("%-36s %8s %8s %8s %8s", "device", "cold_s", "cold_fr", "cached_s", "first_s");
  const std::vector<RenderStats::StageTime> stage_names = RenderStats{}.stage_times();  // the columns
  for (const RenderStats::StageTime& stage : stage_names) std::printf(" %9s", stage.name);
  std::printf(" %9s %9s %9s %9s %9s\n", "other", "frame_s", "records", "rec_Mr/s", "peak_MiB");
  for (const DeviceInfo& device : devices) {
    log_info("bench: " + device.name);
    RenderStats cold;
    std::map<std::string, double> cold_by_file;
    {
      GpuContext gpu(device);
      gpu.use_cold_builds(std::to_string(nonce) + "_" + std::to_string(device.index));
      cold = render(gpu, scene, settings).stats;
      cold_by_file = gpu.program_seconds_by_file();
    }
    { GpuContext gpu(device); render(gpu, scene, settings); }  // fills the program cache when it was empty
    GpuContext gpu(device);  // a new process's state: programs come from the on-disk cache
    Renderer renderer(gpu, scene);
    const FramePlan plan = renderer.plan(settings);
    const RenderStats first = renderer.render(plan).stats;
    std::vector<RenderStats> frames;
    for (int r = 0; r < o.repeats; ++r) frames.push_back(renderer.render(plan).stats);
    auto median_field = [&](auto field) {
      std::vector<double> v;
      for (const RenderStats& s : frames) v.push_back(double(field(s)));
      return median(v);
    };
    const double frame = median_field([](const RenderStats& s) { return s.seconds_without_builds(); });
    const double record_rate = median_field([](const RenderStats& s) {
      return s.irradiance.records_s > 0 ? double(s.irradiance.rays) / s.irradiance.records_s * 1e-6 : 0.0;
    });
    const RenderStats& last = frames.back();
    std::printf("%-36.36s %8.3f %8.3f %8.3f %8.3f", device.name.c_str(), cold.program_s, cold.total_s, first.program_s,
                first.seconds_without_builds());
    nlohmann::json passes;
    for (size_t k = 0; k < stage_names.size(); ++k) {
      const double t = median_field([&](const RenderStats& s) { return s.stage_times()[k].seconds; });
      std::printf(" %9.3f", t);
      passes[stage_names[k].name] = t;
    }
    // What no stage's timer holds (buffers allocated and cleared, setup between passes): frames without builds, less
    // their stages.
    const double other = median_field([](const RenderStats& s) {
      double named = 0.0;
      for (const RenderStats::StageTime& stage : s.stage_times()) named += stage.seconds;
      return s.seconds_without_builds() - named;
    });
    passes["other"] = other;
    std::printf(" %9.3f %9.3f %9llu %9.2f %9.1f\n", other, frame, (unsigned long long)last.irradiance.records,
                record_rate, double(last.device_memory.peak_bytes) / double(1 << 20));
    // The cold builds by file, slowest first: where a first frame's compile time goes.
    std::vector<std::pair<std::string, double>> by_file(cold_by_file.begin(), cold_by_file.end());
    std::stable_sort(by_file.begin(), by_file.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    std::printf("  cold builds by file:");
    for (const auto& [file, seconds] : by_file) std::printf(" %s %.2f s;", file.c_str(), seconds);
    std::printf("\n");
    std::fflush(stdout);
    report["devices"].push_back({{"device", device.name}, {"platform", device.platform_name},
                                 {"kernel_build_cold_by_file_s", cold_by_file},
                                 {"driver", device.driver_version}, {"type", device.type},
                                 {"kernel_build_cold_s", cold.program_s}, {"cold_frame_s", cold.total_s},
                                 {"kernel_build_cached_s", first.program_s},
                                 {"first_frame_s", first.seconds_without_builds()},
                                 {"median_seconds", passes}, {"frame_s", frame}, {"records", last.irradiance.records},
                                 {"record_rays", last.irradiance.rays}, {"record_mrays_per_s", record_rate},
                                 {"bounces", last.bounces.count}, {"pixel_samples", last.primary.pixel_samples},
                                 {"device_peak_bytes", last.device_memory.peak_bytes},
                                 {"device_at_peak_by_use", last.device_memory.at_peak_by_use}});
  }
  std::printf("cold_s, cached_s: what the frame waited for kernel builds (clBuildProgram, side by side ahead of the "
              "passes; cached_s: a new process's, from the on-disk cache); cold builds by file: each build's own "
              "time, overlapping; "
              "cold_fr: the whole cold frame, which holds what a driver compiles at first launch (PoCL does); first_s: "
              "a new renderer's first frame without builds (BVH, upload, probe, photon map included); passes and "
              "frame_s: medians of the frames the same renderer renders next, which keep the BVH, programs, probe, "
              "photon map and light guide; probe: the bounce count's photons; layers: image layers gathered on the "
              "device, downloaded and filled on the host; other: the frame less "
              "its named parts; rec_Mr/s: the "
              "record pass's rays per second; peak_MiB: device buffers at the frame's peak\n");
  report["host_peak_bytes"] = peak_host_bytes();
  if (!o.json_path.empty()) write_text_file(o.json_path, report.dump(2) + "\n");
  return 0;
}

}  // namespace rcsplat
