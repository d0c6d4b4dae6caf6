#include "util/log.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace rcsplat {
namespace {
bool g_quiet = false;
bool g_progress = true;
bool g_progress_lines = false;
int g_last_progress_line = -1;
}

std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  auto escape = [&](unsigned char byte) {
    static const char* digits = "0123456789abcdef";
    out += "\\x";
    out += digits[byte >> 4];
    out += digits[byte & 15];
  };
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
      ++i;
      continue;
    }
    // A UTF-8 sequence of 2 to 4 bytes (no overlong forms, no surrogates, nothing past U+10FFFF) stays; C1 control
    // characters (U+0080..U+009F) do not.
    const size_t length = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    bool valid = length > 0 && i + length <= text.size();
    for (size_t k = 1; valid && k < length; ++k) valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
    if (valid) {
      const unsigned char c1 = static_cast<unsigned char>(text[i + 1]);
      if ((c == 0xe0 && c1 < 0xa0) || (c == 0xed && c1 >= 0xa0) || (c == 0xf0 && c1 < 0x90) || (c == 0xf4 && c1 >= 0x90) ||
          (c == 0xc2 && c1 < 0xa0))
        valid = false;
    }
    if (!valid) {
      escape(c);
      ++i;
      continue;
    }
    out.append(text, i, length);
    i += length;
  }
  return out;
}

void set_quiet(bool quiet) { g_quiet = quiet; }
void set_progress_shown(bool shown) { g_progress = shown; }
bool is_quiet() { return g_quiet; }

void set_progress_lines(bool on) {
  g_progress_lines = on;
  g_last_progress_line = -1;
}

void report_progress(double fraction) {
  if (!g_progress_lines || !(fraction >= 0.0)) return;
  const int percent = int(100.0 * std::min(fraction, 1.0));
  if (percent <= g_last_progress_line) return;
  g_last_progress_line = percent;
  std::printf("Progress: %d%%\n", percent);
  std::fflush(stdout);  // a farm's manager reads the pipe as the task runs
}

void log_info(const std::string& message) {
  if (!g_quiet) std::fprintf(stderr, "%s\n", printable(message).c_str());
}

void log_warning(const std::string& message) { std::fprintf(stderr, "warning: %s\n", printable(message).c_str()); }

Progress::Progress(std::string label, size_t total) : label_(std::move(label)), total_(total ? total : 1) {}

void Progress::update(size_t done) {
  // A pass's 100% is not the command's: only the command reports the whole.
  if (g_progress) report_progress(std::min(double(done) / double(total_), 0.99));
  if (g_quiet || !g_progress) return;
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
  if (!g_quiet && g_progress && isatty(fileno(stderr))) std::fprintf(stderr, "\n");
}

}  // namespace rcsplat
