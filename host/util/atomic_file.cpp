#include "util/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <filesystem>
#include <fstream>

#include "util/error.h"

namespace rcsplat {
namespace fs = std::filesystem;

void check_writable_destination(const std::string& path) {
  fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw Error(path + ": is a directory");
  // The nearest folder that exists: the ones below it are made when the file is written (write_file_atomically).
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  while (!fs::exists(dir, ec) && dir.has_relative_path() && dir.has_parent_path() && dir.parent_path() != dir)
    dir = dir.parent_path();
  if (!fs::exists(dir, ec)) dir = ".";
  if (!fs::is_directory(dir, ec)) throw Error(path + ": " + dir.string() + " is not a directory");
  fs::path probe = dir / (".rcsplat-probe" + std::to_string(getpid()));
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw Error(path + ": cannot create files in " + dir.string() + ": " + std::strerror(errno));
  ::close(fd);
  fs::remove(probe, ec);
}

void write_file_atomically(const std::string& path, const std::function<std::string(const std::string&)>& write) {
  fs::path target(path);
  std::error_code made;
  if (!target.parent_path().empty() && !fs::is_directory(target.parent_path(), made)) {
    fs::create_directories(target.parent_path(), made);
    if (made) throw Error(path + ": cannot create the directory " + target.parent_path().string() + ": " + made.message());
  }
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

void write_text_file(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](const std::string& temp) -> std::string {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    return out.flush() ? "" : "cannot be written";
  });
}

}  // namespace rcsplat
