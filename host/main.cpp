// rcsplat: global illumination by radiance cache splatting on OpenCL devices. Command-line entry point: each command
// registers its own options (cli/command_line.h); main parses and runs the one chosen.
#include <CLI/CLI.hpp>

#include "cli/command_line.h"
#include "util/host_heap.h"
#include "util/log.h"

int main(int argc, char** argv) {
  using namespace rcsplat;
  keep_freed_host_memory();
  std::vector<char*> args(argv, argv + argc);
  const HelpGroups groups = help_groups(args);
  CLI::App app{"rcsplat: global illumination by radiance cache splatting on OpenCL devices"};
  app.require_subcommand(1);
  app.fallthrough();  // -q may follow the subcommand
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "Print only the summary and errors");
  const std::vector<Command> commands = {
      add_devices_command(app, groups), add_render_command(app, groups),  add_animate_command(app, groups),
      add_reference_command(app, groups), add_flicker_command(app, groups), add_info_command(app, groups),
      add_compare_command(app, groups), add_sweep_command(app, groups),   add_bench_command(app, groups)};
  CLI11_PARSE(app, int(args.size()), args.data());
  set_quiet(quiet);
  for (const Command& command : commands)
    if (*command.app) return run_reporting_errors(command.run);
  return 0;
}
