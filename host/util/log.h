// Console messages: warnings and progress go to stderr so that stdout stays clean for summaries.
#pragma once
#include <string>

namespace rcsplat {

void log_info(const std::string& message);
void log_warning(const std::string& message);
void set_quiet(bool quiet);
bool is_quiet();

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
