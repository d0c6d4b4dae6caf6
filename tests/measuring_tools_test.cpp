// The measuring tools of issue 12 as a user runs them: `sweep` (a CSV row of every metric per configuration),
// `bench` (a table row per device, with builds, passes and memory), and the device memory ledger behind both.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cl/gpu_context.h"
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
  // The renders' points (--sub-pixel-grid): at 24 x 18, jittered emitter edges dominate.
  const test::CommandRun reference =
      test::run_rcsplat(dir, {"render", "-o", "ref.exr", "--width", "24", "--height", "18", "--gi", "path", "--spp",
                              "64", "--light-samples", "64", "--stratified", "--sub-pixel-grid", "--bounces", "1"});
  ASSERT_EQ(reference.exit_code, 0) << reference.output;

  const std::vector<std::string> sweep = {"sweep", "--accuracy", "0.5,1", "--hemisphere", "8x16", "--path-spp", "4",
                                          "--denoise", "off", "--no-plot", "--light-samples", "4"};
  auto with = [&](std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  const test::CommandRun run =
      test::run_rcsplat(dir, with(sweep, {"--reference", "ref.exr", "-o", "sweep", "--progress-lines"}));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // A farm manager's lines: a run each, then the whole (tests/cli_outputs.cmake checks render's and animate's).
  EXPECT_NE(run.output.find("Progress: 66%"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Progress: 100%"), std::string::npos) << run.output;
  const std::string output_dir = dir + "/sweep";
  const auto rows = read_csv(output_dir + "/sweep.csv");
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
    EXPECT_TRUE(fs::exists(output_dir + "/" + rows[r][column("config")] + ".exr"));
  }
  EXPECT_EQ(rows[1][column("method")], "cache");
  EXPECT_EQ(rows[1][column("accuracy")], "0.5");
  EXPECT_EQ(rows[3][column("method")], "path");
  EXPECT_EQ(rows[3][column("path_spp")], "4");
  // A coarser cache places fewer records.
  EXPECT_LT(std::stod(rows[2][column("records")]), std::stod(rows[1][column("records")]));

  // A missing reference is named, and nothing is written.
  const test::CommandRun missing = test::run_rcsplat(dir, with(sweep, {"--reference", "missing.exr", "-o", "sweep2"}));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("missing.exr"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(dir + "/sweep2"));
}

TEST(Bench, TablesEachDevicesBuildsPassesAndMemory) {
  const std::string dir = test::scratch_dir();
  // The built-in Cornell box.
  const test::CommandRun run =
      test::run_rcsplat(dir, {"bench", "--width", "16", "--height", "12", "--repeats", "1", "--json", "bench.json"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(dir + "/bench.json");
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
