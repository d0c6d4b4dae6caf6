#include "util/atomic_file.h"

#include <unistd.h>

#include <filesystem>

#include "util/error.h"

namespace rcsplat {
namespace fs = std::filesystem;

void write_file_atomically(const std::string& path, const std::function<std::string(const std::string&)>& write) {
  fs::path target(path);
  // The extension stays last: libraries that pick a format by extension see the target's.
  fs::path temp = target.parent_path() / ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) +
                                          target.extension().string());
  std::string problem = write(temp.string());
  std::error_code ec;
  if (!problem.empty()) {
    fs::remove(temp, ec);
    throw Error(path + ": " + problem);
  }
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw Error(path + ": cannot move the finished file into place: " + ec.message());
  }
}

}  // namespace rcsplat
