// Console messages: warnings and progress go to stderr so that stdout stays clean for summaries.
#pragma once
#include <string>

namespace rcsplat {

// Text safe for a terminal: valid UTF-8 and printable characters as they are, every other byte (control characters,
// escape sequences, broken UTF-8) as \xNN. Names and URIs in a scene are a stranger's text: a message or summary that
// quotes them goes through this (log_info, log_warning and the CLI's error line do).
std::string printable(const std::string& text);

void log_info(const std::string& message);
void log_warning(const std::string& message);
void set_quiet(bool quiet);
// Whether Progress lines are drawn (a command that prints its own progress, a line a frame, turns them off).
void set_progress_shown(bool shown);
// Progress lines hidden while it lives, shown again when it goes (an exception included).
struct ProgressHidden {
  ProgressHidden() { set_progress_shown(false); }
  ~ProgressHidden() { set_progress_shown(true); }
  ProgressHidden(const ProgressHidden&) = delete;
  ProgressHidden& operator=(const ProgressHidden&) = delete;
};
bool is_quiet();
// Render-farm managers (Deadline and others) read a task's progress from stdout lines "Progress: NN%". With these on
// (--progress-lines), report_progress prints one whenever the whole percentage grows (never going back, whatever
// reports it), -q or not, and every Progress shown reports its own fraction through it.
void set_progress_lines(bool on);
void report_progress(double fraction);

// A one-line progress indicator, redrawn in place on a terminal and printed at each quarter otherwise.
class Progress {
 public:
  Progress(std::string label, size_t total);
  void update(size_t done);
  void finish();

 private:
  std::string label_;
  size_t total_;
  int last_percent_ = -1;
  bool finished_ = false;
};

}  // namespace rcsplat
