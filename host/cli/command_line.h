// What the commands share on the command line: each command registers its own options in its own file (add_*_command
// in cli/commands.h) from these groups, and main() only parses and runs the one chosen.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace rcsplat {

// A registered command: its CLI11 subcommand and what runs it once the command line is parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

// The group experiment options are listed under: shown by --help-all, hidden ("") by --help.
struct HelpGroups {
  std::string lab;
  bool help_all = false;
};

// A number as the help texts print it (%g).
std::string shortest(float v);

// --eye, --target, --up, --fov.
struct CameraFlags {
  std::vector<float> eye, target, up;
  std::optional<float> fov;
  void apply(RenderSettings& s) const;
};

// Light from outside the scene (scene/environment.h), for render, reference, info and sweep.
struct EnvironmentFlags {
  std::vector<float> sky;
  std::string light_through_glass = "straight";
  void add(CLI::App* cmd, EnvironmentSettings& e);
  void apply(EnvironmentSettings& e) const;
};

// What a scene may make rcsplat read and hold (scene/scene_limits.h, docs/SECURITY.md): for every command that loads
// one. --max-device-memory only where a frame is rendered.
void add_scene_limit_options(CLI::App* cmd, SceneLimits& limits, bool device);

// The options every image-making command shares: scene, outputs, device, frame and camera, light samples, and the
// summary's JSON and progress lines.
void add_frame_options(CLI::App* cmd, RenderJob& job, std::string& json_path, bool& progress_lines, CameraFlags& cam,
                       EnvironmentFlags& env, const HelpGroups& groups);

// How `render` and `animate` compute a frame: the quality preset, the indirect-light method and the cache's options.
struct RenderMethodFlags {
  std::string gi = "splat", hemisphere, spacing, fine_hemisphere, bounce_method;
  bool glossy_paths = false, glossy_uniform = false, light_uniform = false;
  void add(CLI::App* cmd, RenderJob& job, std::string& quality, const HelpGroups& groups);
  // After parsing: the strings parsed into the settings, then the quality preset under the options given.
  void apply(CLI::App* cmd, RenderJob& job, const std::string& quality) const;
};

// The commands, each registering its options in its own file (cli/<name>_command.cpp; reference's in
// cli/reference_resume.cpp), in the order `rcsplat --help` lists them.
Command add_devices_command(CLI::App& app, const HelpGroups& groups);
Command add_render_command(CLI::App& app, const HelpGroups& groups);
Command add_animate_command(CLI::App& app, const HelpGroups& groups);
Command add_reference_command(CLI::App& app, const HelpGroups& groups);
Command add_flicker_command(CLI::App& app, const HelpGroups& groups);
Command add_info_command(CLI::App& app, const HelpGroups& groups);
Command add_compare_command(CLI::App& app, const HelpGroups& groups);
Command add_sweep_command(CLI::App& app, const HelpGroups& groups);
Command add_bench_command(CLI::App& app, const HelpGroups& groups);

// `--help-all` in argv becomes `--help` with the experiment options' group shown (hidden otherwise).
HelpGroups help_groups(std::vector<char*>& args);

// Runs a parsed command, turning what escapes it into one "error: ..." line on stderr and exit code 1.
int run_reporting_errors(const std::function<int()>& run);

}  // namespace rcsplat
