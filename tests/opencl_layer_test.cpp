// The OpenCL layer: device listing, kernel build errors mapped to file and line, determinism of a render.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "cl/device_info.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

TEST(OpenClLayer, ListsAUsableDevice) {
  std::vector<DeviceInfo> devices = list_devices();
  ASSERT_FALSE(devices.empty());
  bool usable = false;
  for (const DeviceInfo& d : devices) usable |= d.usable() && d.int64_atomics;
  EXPECT_TRUE(usable);
  EXPECT_THROW(select_device("no device has this name"), Error);
  EXPECT_THROW(select_device("999"), Error);
}

TEST(OpenClLayer, IncludesAreResolvedWithLineDirectives) {
  std::string source = resolve_kernel_source("ray_cast.cl");
  EXPECT_NE(source.find("#line 1 \"kernels/traverse.h\""), std::string::npos);
  EXPECT_NE(source.find("#line 1 \"kernels/shared_types.h\""), std::string::npos);
  EXPECT_EQ(source.find("#include \""), std::string::npos);
}

TEST(OpenClLayer, BuildFailureNamesFileAndLine) {
  // Developer mode: kernels read from a folder, here a copy with an error planted on a known line.
  std::string dir = test::scratch_dir();
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(RCSPLAT_SOURCE_DIR) / "kernels"))
    std::filesystem::copy_file(entry.path(), std::filesystem::path(dir) / entry.path().filename());
  test::write_file(dir + "/broken.cl", "#include \"shared_types.h\"\n__kernel void k(__global float* x) {\n  x[0] = undeclared_name;\n}\n");
  setenv("RCSPLAT_KERNEL_DIR", dir.c_str(), 1);
  try {
    test::gpu().program("broken.cl");
    ADD_FAILURE() << "the broken kernel built";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("kernels/broken.cl:3"), std::string::npos) << message;
    EXPECT_NE(message.find("undeclared_name"), std::string::npos) << message;
  }
  unsetenv("RCSPLAT_KERNEL_DIR");
}

TEST(OpenClLayer, SameInputSameImage) {
  Scene scene = make_cornell_box();
  RenderSettings settings = test::one_bounce_one_sample();
  settings.gi = GiMethod::none;
  settings.width = settings.height = 40;
  RenderedImage a = render(test::gpu(), scene, settings);
  RenderedImage b = render(test::gpu(), scene, settings);
  EXPECT_EQ(a.color, b.color);
  settings.seed = 1;
  RenderedImage c = render(test::gpu(), scene, settings);
  EXPECT_NE(a.color, c.color);  // the seed changes the sample pattern
  for (float v : a.color) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace rcsplat
