#include "util/log.h"

#include <unistd.h>

#include <cstdio>

namespace rcsplat {
namespace {
bool g_quiet = false;
}

void set_quiet(bool quiet) { g_quiet = quiet; }
bool is_quiet() { return g_quiet; }

void log_info(const std::string& message) {
  if (!g_quiet) std::fprintf(stderr, "%s\n", message.c_str());
}

void log_warning(const std::string& message) { std::fprintf(stderr, "warning: %s\n", message.c_str()); }

Progress::Progress(std::string label, size_t total) : label_(std::move(label)), total_(total ? total : 1) {}

void Progress::update(size_t done) {
  if (g_quiet) return;
  int percent = int(100.0 * double(done) / double(total_));
  if (percent == last_percent_) return;
  bool tty = isatty(fileno(stderr));
  if (tty) {
    std::fprintf(stderr, "\r%s %3d%%", label_.c_str(), percent);
  } else if (percent / 25 != last_percent_ / 25 || last_percent_ < 0) {
    std::fprintf(stderr, "%s %3d%%\n", label_.c_str(), percent);
  }
  last_percent_ = percent;
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  update(total_);
  if (!g_quiet && isatty(fileno(stderr))) std::fprintf(stderr, "\n");
}

}  // namespace rcsplat
