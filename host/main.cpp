// rcsplat: global illumination by radiance cache splatting on OpenCL devices. Command-line entry point.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/commands.h"
#include "util/error.h"
#include "util/log.h"

namespace {

std::optional<glm::vec3> as_vec3(const std::vector<float>& v) {
  if (v.empty()) return std::nullopt;
  return glm::vec3(v[0], v[1], v[2]);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rcsplat;
  CLI::App app{"rcsplat: global illumination by radiance cache splatting on OpenCL devices"};
  app.require_subcommand(1);
  app.fallthrough();  // -q may follow the subcommand
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "Print only the summary and errors");

  DevicesOptions devices;
  CLI::App* devices_cmd = app.add_subcommand("devices", "List OpenCL platforms and devices, and whether rcsplat can use them");
  devices_cmd->add_option("--json", devices.json_path, "Also write the list as JSON");

  RenderOptions render;
  std::vector<float> eye, target, up;
  std::optional<float> fov;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a glTF scene (default: the built-in Cornell box)");
  render_cmd->add_option("scene", render.scene_path, "glTF 2.0 scene (.gltf or .glb)");
  render_cmd->add_option("-o,--output", render.outputs, "Output image(s): .exr (linear, with layers) or .png (tone-mapped)")
      ->required();
  render_cmd->add_option("--device", render.device, "OpenCL device: index or name substring (see `rcsplat devices`)");
  render_cmd->add_option("--width", render.settings.width, "Image width in pixels")->check(CLI::Range(1, 16384));
  render_cmd->add_option("--height", render.settings.height, "Image height in pixels")->check(CLI::Range(1, 16384));
  render_cmd->add_option("--camera", render.settings.camera, "Index of the scene camera to use")->check(CLI::NonNegativeNumber);
  render_cmd->add_option("--eye", eye, "Camera position x,y,z")->delimiter(',')->expected(3);
  render_cmd->add_option("--target", target, "Point the camera looks at x,y,z")->delimiter(',')->expected(3);
  render_cmd->add_option("--up", up, "Camera up vector x,y,z")->delimiter(',')->expected(3);
  render_cmd->add_option("--fov", fov, "Vertical field of view in degrees");
  render_cmd->add_option("--light-samples", render.settings.light_samples,
                         "Samples per pixel on emissive triangles (rounded up to a square)")
      ->check(CLI::Range(0u, 65536u));
  render_cmd->add_option("--seed", render.settings.seed, "Seed of the sample pattern");
  render_cmd->add_option("--exposure", render.exposure, "PNG exposure in stops");
  render_cmd->add_option("--json", render.json_path, "Also write the summary as JSON");

  BenchOptions bench;
  CLI::App* bench_cmd = app.add_subcommand("bench", "Traversal speed: the OpenCL kernel against Embree on the same rays");
  bench_cmd->add_option("scene", bench.scene_path, "glTF scene (default: ../shared/scenes Sponza, else a generated one)");
  bench_cmd->add_option("--device", bench.device, "OpenCL device: index or name substring");
  bench_cmd->add_option("--rays", bench.rays, "Rays in the incoherent pattern")->check(CLI::Range(size_t(1), size_t(1) << 26));
  bench_cmd->add_option("--record-points", bench.record_points, "Points for the 256-ray record pattern")
      ->check(CLI::Range(size_t(1), size_t(1) << 18));
  bench_cmd->add_option("--repeats", bench.repeats, "Paired runs (medians are reported)")->check(CLI::Range(1, 1000));
  bench_cmd->add_option("--json", bench.json_path, "Also write the results as JSON");

  CLI11_PARSE(app, argc, argv);
  set_quiet(quiet);
  try {
    if (*devices_cmd) return run_devices(devices);
    if (*render_cmd) {
      render.settings.camera_overrides.eye = as_vec3(eye);
      render.settings.camera_overrides.target = as_vec3(target);
      render.settings.camera_overrides.up = as_vec3(up);
      render.settings.camera_overrides.fov_degrees = fov;
      return run_render(render);
    }
    if (*bench_cmd) return run_bench(bench);
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const cl::Error& e) {
    std::fprintf(stderr, "error: OpenCL call %s failed with code %d\n", e.what(), e.err());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
