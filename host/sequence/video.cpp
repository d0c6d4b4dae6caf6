#include "sequence/video.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "util/atomic_file.h"

extern char** environ;

namespace rcsplat {
namespace {

// The path of `program` found on PATH, or "".
std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::string candidate = dir + "/" + program;
    if (access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return "";
}

// Runs a program with these arguments (no shell: the names are the user's), waits; its exit status, -1 if not run.
int run_program(const std::string& program, const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string find_ffmpeg() { return find_on_path("ffmpeg"); }

void encode_mp4(const std::string& ffmpeg, const std::string& png_pattern, long long first, long long count,
                double fps, const std::string& path) {
  write_file_atomically(path, [&](const std::string& temp) -> std::string {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.9g", fps);
    const int status = run_program(ffmpeg, {"-y",
                                            "-loglevel",
                                            "error",
                                            "-framerate",
                                            rate,
                                            "-start_number",
                                            std::to_string(first),
                                            "-i",
                                            png_pattern,
                                            "-frames:v",
                                            std::to_string(count),
                                            "-c:v",
                                            "libx264",
                                            "-pix_fmt",
                                            "yuv420p",
                                            "-vf",
                                            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                            "-f",
                                            "mp4",
                                            temp});
    return status == 0 ? "" : "ffmpeg failed (exit status " + std::to_string(status) + ")";
  });
}

}  // namespace rcsplat
