#include "test_support.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <sstream>
#include <thread>

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

CommandRun run_rcsplat(const std::string& folder, const std::vector<std::string>& args, int limit_seconds) {
  const std::chrono::seconds limit(limit_seconds);
  // The output goes to a file of its own outside `folder`, which tests check for what the command left behind.
  static int runs = 0;
  const std::filesystem::path log_dir = std::filesystem::path(scratch_dir()).parent_path() / "command-runs";
  std::filesystem::create_directories(log_dir);
  const std::filesystem::path log = log_dir / ("rcsplat-run" + std::to_string(++runs) + ".txt");
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(folder.c_str()) != 0) _exit(127);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> argv;
    std::string binary = RCSPLAT_BINARY;
    argv.push_back(binary.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  CommandRun run;
  int status = 0;
  struct rusage usage {};
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() - start > limit) {
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      ADD_FAILURE() << "still running after " << limit.count() << " s: killed";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.peak_memory_kib = usage.ru_maxrss;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

}  // namespace rcsplat::test
