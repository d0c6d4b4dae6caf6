#include <cstdio>
#include <nlohmann/json.hpp>

#include "cl/device_info.h"
#include "cli/command_line.h"
#include "cli/commands.h"
#include "util/atomic_file.h"

namespace rcsplat {

int run_devices(const DevicesOptions& options) {
  std::vector<DeviceInfo> devices = list_devices();
  nlohmann::json list = nlohmann::json::array();
  if (devices.empty()) std::printf("no OpenCL platform or device found\n");
  for (const DeviceInfo& d : devices) {
    std::printf("[%zu] %s (%s)\n", d.index, d.name.c_str(), d.platform_name.c_str());
    std::printf("    type %s, %u compute units, %.1f GiB global memory (largest buffer %.1f GiB)\n", d.type.c_str(),
                d.compute_units, double(d.global_memory) / double(1ull << 30), double(d.max_allocation) / double(1ull << 30));
    std::printf("    %s, %s, driver %s\n", d.version.c_str(), d.opencl_c_version.c_str(), d.driver_version.c_str());
    std::printf("    64-bit integer atomics: %s\n", d.int64_atomics ? "yes" : "no");
    if (d.usable()) {
      std::printf("    usable by rcsplat: yes\n");
    } else {
      std::printf("    usable by rcsplat: no:");
      for (const std::string& p : d.problems) std::printf(" %s;", p.c_str());
      std::printf("\n");
    }
    list.push_back({{"index", d.index}, {"name", d.name}, {"platform", d.platform_name}, {"type", d.type},
                    {"compute_units", d.compute_units}, {"global_memory_bytes", d.global_memory},
                    {"version", d.version}, {"opencl_c_version", d.opencl_c_version}, {"driver", d.driver_version},
                    {"int64_atomics", d.int64_atomics}, {"usable", d.usable()}, {"problems", d.problems}});
  }
  if (!options.json_path.empty()) write_text_file(options.json_path, list.dump(2) + "\n");
  return 0;
}

Command add_devices_command(CLI::App& app, const HelpGroups&) {
  auto options = std::make_shared<DevicesOptions>();
  CLI::App* cmd = app.add_subcommand("devices", "List OpenCL platforms and devices, and whether rcsplat can use them");
  cmd->add_option("--json", options->json_path, "Also write the list as JSON");
  return {cmd, [options] { return run_devices(*options); }};
}

}  // namespace rcsplat
