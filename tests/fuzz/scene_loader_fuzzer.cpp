// libFuzzer target: scene loading and validation (glTF and GLB through tinygltf and rcsplat's loader), then everything
// the renderer derives from a scene on the host before the device sees it (default view, camera, device frame,
// packed arrays). A malformed file must end in rcsplat::Error; anything else (a crash, a sanitizer report, or a
// non-finite value handed on to the kernels) is a bug. Built with -DRCSPLAT_BUILD_FUZZER=ON by clang; scripts/fuzz.sh.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/camera.h"
#include "scene/gltf_loader.h"
#include "scene/packed_scene.h"
#include "scene/scene_frame.h"
#include "util/error.h"
#include "util/log.h"

namespace {

const std::string& scratch() {
  static const std::string dir = [] {
    std::filesystem::path p = std::filesystem::temp_directory_path() / ("rcsplat-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(p);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() / ("rcsplat-fuzz-" + std::to_string(getpid())), ec);
    });
    return p.string();
  }();
  return dir;
}

void require_finite(const float* values, size_t count, const char* what) {
  for (size_t i = 0; i < count; ++i)
    if (!std::isfinite(values[i])) {
      std::fprintf(stderr, "accepted scene hands a non-finite %s to the kernels\n", what);
      std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rcsplat::set_quiet(true);
  const bool binary = size >= 4 && std::string(reinterpret_cast<const char*>(data), 4) == "glTF";
  const std::string path = scratch() + (binary ? "/input.glb" : "/input.gltf");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    // Limits well inside libFuzzer's 2 GB: a file that reaches one must be refused, not run out of memory.
    rcsplat::SceneLimits limits;
    limits.host_memory_bytes = uint64_t(512) << 20;
    limits.max_triangles = uint64_t(1) << 20;
    rcsplat::Scene scene = rcsplat::load_gltf(path, limits);
    rcsplat::add_view_defaults(scene, 0, {});
    rcsplat::SceneCamera camera = rcsplat::choose_camera(scene, 0, {});
    int width = 64, height = 0;
    rcsplat::resolve_resolution(camera, width, height);
    const rcsplat::SceneFrame frame = rcsplat::SceneFrame::fitted(scene);
    CameraParams params = rcsplat::camera_params(frame.device_camera(camera), width, height);
    for (const float* v : {params.eye, params.right, params.up, params.forward}) require_finite(v, 3, "camera vector");
    require_finite(&params.tan_half_fov_y, 1, "camera field of view");
    require_finite(&params.half_height, 1, "camera height");
    rcsplat::PackedScene packed = rcsplat::pack_scene(scene, frame);
    for (const TriangleShading& t : packed.triangles) {
      require_finite(t.v0, 3, "vertex");
      require_finite(t.v1, 3, "vertex");
      require_finite(t.v2, 3, "vertex");
      require_finite(t.normal0, 3, "normal");
      require_finite(t.normal1, 3, "normal");
      require_finite(t.normal2, 3, "normal");
      require_finite(t.geometric_normal, 3, "geometric normal");
    }
    for (const Material& m : packed.materials) require_finite(m.base_color, 4, "material factor");
    for (const PunctualLight& l : packed.lights) require_finite(l.intensity, 3, "light intensity");
    for (const EmissiveTriangle& e : packed.emitters) require_finite(&e.cdf, 1, "emitter CDF");
  } catch (const rcsplat::Error&) {
    // A clear refusal: what the loader must do with a malformed file.
  }
  return 0;
}
