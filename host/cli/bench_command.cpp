// `rcsplat bench --traversal`: the device traversal against Embree's rtcIntersect1 on all cores, on the same incoherent
// hemisphere rays, paired run by run because the machine's speed drifts; on the record pattern also against Embree's
// packets (rtcIntersect8/16 of consecutive rays, which share an origin), the fairer opponent there.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "bench/ray_sets.h"
#include "bvh/bvh8.h"
#include "bvh/embree_scene.h"
#include "cl/device_info.h"
#include "cl/device_scene.h"
#include "cli/command_line.h"
#include "cli/commands.h"
#include "util/atomic_file.h"
#include "passes/ray_cast_pass.h"
#include "scene/procedural.h"
#include "util/log.h"
#include "util/median.h"

namespace rcsplat {
namespace {

// Seconds to run body(i, n) over [0, count) in steps of `step` (n <= step items from i), 4096-item chunks dealt in
// turn to one thread per hardware thread (4096 is a multiple of every step: a step never straddles two chunks).
template <typename Body>
double seconds_on_all_threads(size_t count, size_t step, const Body& body) {
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      const size_t chunk = 4096;
      for (size_t begin = t * chunk; begin < count; begin += threads * chunk)
        for (size_t i = begin; i < std::min(count, begin + chunk); i += step) body(i, std::min(count - i, step));
    });
  }
  for (std::thread& th : pool) th.join();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Seconds for Embree to trace all rays with one thread per hardware thread.
double embree_seconds(const EmbreeScene& embree, const std::vector<RayDesc>& rays, std::vector<EmbreeHit>& hits) {
  hits.resize(rays.size());
  return seconds_on_all_threads(rays.size(), 1, [&](size_t i, size_t) {
    const RayDesc& r = rays[i];
    hits[i] = embree.intersect(ray_origin(r), ray_direction(r), r.tmin, r.tmax);
  });
}

// Seconds for Embree to trace all rays as packets of `width` consecutive rays (8 or 16), one thread per hardware
// thread.
double embree_packet_seconds(const EmbreeScene& embree, const std::vector<RayDesc>& rays, int width,
                             std::vector<EmbreeHit>& hits) {
  hits.resize(rays.size());
  std::vector<glm::vec3> org(rays.size()), dir(rays.size());
  std::vector<float> tmin(rays.size()), tmax(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    org[i] = ray_origin(rays[i]);
    dir[i] = ray_direction(rays[i]);
    tmin[i] = rays[i].tmin;
    tmax[i] = rays[i].tmax;
  }
  return seconds_on_all_threads(rays.size(), size_t(width), [&](size_t i, size_t n) {
    embree.intersect_packet(width, int(n), &org[i], &dir[i], &tmin[i], &tmax[i], &hits[i]);
  });
}

size_t hit_miss_disagreements(const std::vector<HitDesc>& a, const std::vector<EmbreeHit>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if ((a[i].prim < 0) != (b[i].prim < 0)) ++n;
  return n;
}

}  // namespace

std::string default_bench_scene() {
  for (const char* root : {RCSPLAT_SOURCE_DIR, "."}) {
    std::filesystem::path p = std::filesystem::path(root) / ".." / "shared" / "scenes" / "sponza_dabrovic" / "sponza.gltf";
    if (std::filesystem::exists(p)) return p.lexically_normal().string();
  }
  return "";
}

int run_bench(const BenchOptions& options) {
  if (!options.traversal) return run_bench_frames(options);
  std::string path = options.scene_path.empty() ? default_bench_scene() : options.scene_path;
  Scene scene;
  if (path.empty()) {
    log_warning("../shared/scenes/sponza_dabrovic is absent: benchmarking a generated room of 5,000 boxes instead");
    scene = make_box_room(5000, 7);
  } else {
    scene = load_scene(path, 0, {}, {}, options.limits);
  }
  DeviceInfo device = select_device(options.device);
  log_info("scene " + scene.source + ", " + std::to_string(scene.triangle_count()) + " triangles; device " + device.name);

  EmbreeScene embree(scene.positions);
  Bvh8 bvh = build_bvh8(scene.positions);
  GpuContext gpu(device);
  DeviceScene device_scene(gpu, scene, bvh);
  RayCastPass caster(gpu, device_scene);

  std::vector<SurfaceSample> points = camera_visible_points(scene, embree, options.rays, 1);
  struct Pattern {
    std::string name;
    std::vector<RayDesc> rays;
    bool packets;  // also against Embree's packets
  };
  std::vector<Pattern> patterns;
  patterns.push_back({"A: one cosine ray from each of " + std::to_string(points.size()) + " visible points",
                      incoherent_hemisphere_rays(points, 2), false});
  points.resize(std::min(points.size(), options.record_points));
  patterns.push_back({"B: 16 x 16 stratified cosine rays from each of " + std::to_string(points.size()) + " points",
                      record_hemisphere_rays(points, 16, 3), true});

  nlohmann::json report = {{"scene", scene.source}, {"triangles", scene.triangle_count()}, {"device", device.name},
                           {"embree_threads", std::max(1u, std::thread::hardware_concurrency())},
                           {"bvh", {{"nodes", bvh.nodes.size()}, {"blocks", bvh.blocks.size()}, {"depth", bvh.depth},
                                    {"build_seconds", bvh.build_seconds}}}};
  std::printf("scene %s (%zu triangles), device %s, Embree on %u threads, %d paired runs, medians\n",
              scene.source.c_str(), scene.triangle_count(), device.name.c_str(),
              std::max(1u, std::thread::hardware_concurrency()), options.repeats);
  for (Pattern& pattern : patterns) {
    caster.set_rays(pattern.rays);
    std::vector<EmbreeHit> embree_hits;
    caster.cast_closest();  // warm-up: first-run allocation and caches
    embree_seconds(embree, pattern.rays, embree_hits);
    std::vector<EmbreeHit> packet_hits[2];
    if (pattern.packets) {
      embree_packet_seconds(embree, pattern.rays, 8, packet_hits[0]);
      embree_packet_seconds(embree, pattern.rays, 16, packet_hits[1]);
    }
    std::vector<double> embree_rate, device_rate, ratio, packet_rate[2], packet_ratio[2], best_ratio;
    for (int r = 0; r < options.repeats; ++r) {
      double te = embree_seconds(embree, pattern.rays, embree_hits);
      double tp[2] = {0.0, 0.0};
      if (pattern.packets) {
        tp[0] = embree_packet_seconds(embree, pattern.rays, 8, packet_hits[0]);
        tp[1] = embree_packet_seconds(embree, pattern.rays, 16, packet_hits[1]);
      }
      double td = caster.cast_closest();
      double n = double(pattern.rays.size());
      embree_rate.push_back(n / te * 1e-6);
      device_rate.push_back(n / td * 1e-6);
      ratio.push_back(te / td);
      double best = te;
      for (int k = 0; k < 2 && pattern.packets; ++k) {
        packet_rate[k].push_back(n / tp[k] * 1e-6);
        packet_ratio[k].push_back(tp[k] / td);
        best = std::min(best, tp[k]);
      }
      best_ratio.push_back(best / td);
    }
    // Agreement check, so that a fast but wrong kernel cannot pass unnoticed.
    std::vector<HitDesc> hits = caster.closest_hits();
    size_t disagree = hit_miss_disagreements(hits, embree_hits);
    std::printf("%s\n  Embree %.2f Mrays/s, OpenCL %.2f Mrays/s, ratio %.3f (hit/miss disagreements: %zu of %zu)\n",
                pattern.name.c_str(), median(embree_rate), median(device_rate), median(ratio), disagree, hits.size());
    nlohmann::json row = {{"name", pattern.name}, {"rays", pattern.rays.size()},
                          {"embree_mrays_per_s", median(embree_rate)},
                          {"opencl_mrays_per_s", median(device_rate)}, {"ratio", median(ratio)},
                          {"hit_miss_disagreements", disagree}};
    if (pattern.packets) {
      for (int k = 0; k < 2; ++k) {
        const int width = k == 0 ? 8 : 16;
        const size_t packet_disagree = hit_miss_disagreements(hits, packet_hits[k]);
        std::printf("  Embree rtcIntersect%d (coherent packets of consecutive rays) %.2f Mrays/s, ratio %.3f "
                    "(disagreements: %zu)\n",
                    width, median(packet_rate[k]), median(packet_ratio[k]), packet_disagree);
        row["embree_packet" + std::to_string(width)] = {{"mrays_per_s", median(packet_rate[k])},
                                                        {"ratio", median(packet_ratio[k])},
                                                        {"hit_miss_disagreements", packet_disagree}};
      }
      std::printf("  against Embree's best of the three: ratio %.3f\n", median(best_ratio));
      row["ratio_to_best_embree"] = median(best_ratio);
    }
    report["patterns"].push_back(row);
  }
  if (!options.json_path.empty()) write_text_file(options.json_path, report.dump(2) + "\n");
  return 0;
}

Command add_bench_command(CLI::App& app, const HelpGroups&) {
  auto o = std::make_shared<BenchOptions>();
  const BenchOptions defaults;
  CLI::App* cmd = app.add_subcommand(
      "bench", "The same frame on each OpenCL device (kernel builds, time per pass, memory), or --traversal");
  cmd->add_option("scene", o->scene_path,
                  "glTF scene (default: the built-in Cornell box; for --traversal ../shared/scenes Sponza, else a "
                  "generated one)");
  cmd->add_option("--devices", o->devices,
                  "Devices to compare: all (every usable one) or a comma-separated list of indices or name parts; "
                  "default: the default device");
  cmd->add_option("--device", o->device, "One OpenCL device: index or name substring");
  cmd->add_option("--width", o->width, "Frame width (default " + std::to_string(defaults.width) + ")")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", o->height, "Frame height (default " + std::to_string(defaults.height) + ")")
      ->check(CLI::Range(1, 16384));
  cmd->add_flag("--traversal", o->traversal, "Instead: the traversal kernel against Embree's rtcIntersect1 on the same rays");
  cmd->add_option("--rays", o->rays, "--traversal: rays in the incoherent pattern")
      ->check(CLI::Range(size_t(1), size_t(1) << 26));
  cmd->add_option("--record-points", o->record_points, "--traversal: points for the 256-ray record pattern")
      ->check(CLI::Range(size_t(1), size_t(1) << 18));
  cmd->add_option("--repeats", o->repeats,
                  "Timed frames per device (default " + std::to_string(kBenchFrameRepeats) +
                      "), or --traversal's paired runs (default " + std::to_string(kBenchTraversalRepeats) +
                      "); medians")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--json", o->json_path, "Also write the results as JSON");
  add_scene_limit_options(cmd, o->limits, false);
  return {cmd, [o, cmd] {
            if (!o->traversal && cmd->count("--repeats") == 0) o->repeats = kBenchFrameRepeats;
            return run_bench(*o);
          }};
}

}  // namespace rcsplat
