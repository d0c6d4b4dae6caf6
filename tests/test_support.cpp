#include "test_support.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "cl/device_info.h"

namespace rcsplat::test {

std::unique_ptr<GpuContext> fresh_gpu() {
  const char* selector = std::getenv("RCSPLAT_TEST_DEVICE");
  return std::make_unique<GpuContext>(select_device(selector ? selector : ""));
}

GpuContext& gpu() {
  static std::unique_ptr<GpuContext> context = fresh_gpu();
  return *context;
}

std::string scratch_dir() {
  static std::filesystem::path root = [] {
    std::filesystem::path p = std::filesystem::temp_directory_path() / ("rcsplat-test-" + std::to_string(getpid()));
    std::filesystem::create_directories(p);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() / ("rcsplat-test-" + std::to_string(getpid())), ec);
    });
    return p;
  }();
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = root / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return dir.string();
}

void write_file(const std::string& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
}

}  // namespace rcsplat::test
