// The measuring tools of issue 12 as a user runs them: `sweep` (a CSV row of every metric per configuration),
// `bench` (a table row per device, with builds, passes and memory), and the device memory ledger behind both.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cl/gpu_context.h"
#include "cli/commands.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

namespace fs = std::filesystem;

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

TEST(Sweep, WritesEveryConfigurationsTimeAndErrorsToTheCsv) {
  const std::string dir = test::scratch_dir();
  RenderOptions reference;
  reference.outputs = {dir + "/ref.exr"};
  reference.settings.width = 24;
  reference.settings.height = 18;
  reference.settings.gi = GiMethod::path;
  reference.settings.path.samples = 64;
  reference.settings.light_samples = 64;
  reference.settings.path.stratified = true;
  reference.settings.path.pixel_area = false;  // the renders' points: at 24 x 18, jittered emitter edges dominate
  reference.settings.bounces = 1;
  ASSERT_EQ(run_render(reference), 0);

  SweepOptions o;
  o.reference_path = dir + "/ref.exr";
  o.output_dir = dir + "/sweep";
  o.accuracies = {0.5f, 1.0f};
  o.hemispheres = {"8x16"};
  o.path_samples = {4};
  o.denoise = "off";
  o.plot = false;
  o.light_samples = 4;
  ASSERT_EQ(run_sweep(o), 0);
  const auto rows = read_csv(o.output_dir + "/sweep.csv");
  ASSERT_EQ(rows.size(), 4u);  // the header, two cache settings, one path-traced count
  const std::vector<std::string>& header = rows[0];
  auto column = [&](const std::string& name) {
    auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return size_t(it - header.begin());
  };
  for (size_t r = 1; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), header.size()) << "row " << r;
    EXPECT_GT(std::stod(rows[r][column("seconds")]), 0.0);
    EXPECT_EQ(rows[r][column("bounces")], "1");  // the reference's
    for (const char* metric : {"full_rel_mse", "indirect_rel_mse", "indirect_block_rel_mse", "indirect_flip",
                               "indirect_rel_mse_less_noise"}) {
      const double v = std::stod(rows[r][column(metric)]);
      EXPECT_TRUE(std::isfinite(v)) << metric;
      EXPECT_LT(std::abs(v), 1.0) << metric << " in row " << r;
    }
    EXPECT_TRUE(fs::exists(o.output_dir + "/" + rows[r][column("config")] + ".exr"));
  }
  EXPECT_EQ(rows[1][column("method")], "cache");
  EXPECT_EQ(rows[1][column("accuracy")], "0.5");
  EXPECT_EQ(rows[3][column("method")], "path");
  EXPECT_EQ(rows[3][column("path_spp")], "4");
  // A coarser cache places fewer records.
  EXPECT_LT(std::stod(rows[2][column("records")]), std::stod(rows[1][column("records")]));

  // A missing reference is named, and nothing is written.
  o.reference_path = dir + "/missing.exr";
  o.output_dir = dir + "/sweep2";
  try {
    run_sweep(o);
    ADD_FAILURE() << "a missing reference was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.exr"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(o.output_dir));
}

TEST(Bench, TablesEachDevicesBuildsPassesAndMemory) {
  const std::string dir = test::scratch_dir();
  BenchOptions o;
  // The built-in Cornell box.
  o.width = 16;
  o.height = 12;
  o.repeats = 1;
  o.json_path = dir + "/bench.json";
  ASSERT_EQ(run_bench(o), 0);
  std::ifstream in(o.json_path);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["devices"].size(), 1u) << j.dump();
  const nlohmann::json& d = j["devices"][0];
  EXPECT_GT(d["kernel_build_cold_s"].get<double>(), 0.0);
  EXPECT_GE(d["cold_frame_s"].get<double>(), d["kernel_build_cold_s"].get<double>());
  EXPECT_GT(d["frame_s"].get<double>(), 0.0);
  EXPECT_GT(d["median_seconds"]["records"].get<double>(), 0.0);
  EXPECT_GT(d["records"].get<uint64_t>(), 0u);
  EXPECT_GT(d["device_at_peak_by_use"]["G-buffer"].get<uint64_t>(), 16u * 12u);
  EXPECT_GT(d["device_peak_bytes"].get<uint64_t>(), d["device_at_peak_by_use"]["G-buffer"].get<uint64_t>());
  EXPECT_GT(j["host_peak_bytes"].get<uint64_t>(), 0u);
}

TEST(DeviceMemory, CountsBuffersUntilOpenClFreesThem) {
  GpuContext& gpu = test::gpu();
  gpu.restart_memory_peak();
  const DeviceMemoryUse before = gpu.memory_use();
  {
    cl::Buffer a = gpu.buffer(CL_MEM_READ_WRITE, 1 << 20, "test a");
    cl::Buffer b = gpu.upload(std::vector<float>(1000, 1.0f), CL_MEM_READ_ONLY, "test b");
    const DeviceMemoryUse during = gpu.memory_use();
    EXPECT_EQ(during.live_bytes, before.live_bytes + (1 << 20) + 4000);
    EXPECT_EQ(during.live_by_use.at("test a"), size_t(1) << 20);
    EXPECT_EQ(during.live_by_use.at("test b"), 4000u);
  }
  gpu.queue().finish();
  const DeviceMemoryUse after = gpu.memory_use();
  EXPECT_EQ(after.live_bytes, before.live_bytes);
  EXPECT_EQ(after.live_by_use.count("test a"), 0u);
  EXPECT_EQ(after.peak_bytes, before.live_bytes + (1 << 20) + 4000);
  EXPECT_EQ(after.at_peak_by_use.at("test a"), size_t(1) << 20);
}

}  // namespace
}  // namespace rcsplat
