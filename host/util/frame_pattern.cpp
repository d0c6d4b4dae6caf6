#include "util/frame_pattern.h"

#include <string>

#include "util/error.h"

namespace rcsplat {

FramePattern::FramePattern(const std::string& pattern, const std::string& option) : pattern_(pattern) {
  bool found = false;
  std::string* part = &prefix_;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      *part += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      *part += '%';
      ++i;
      continue;
    }
    size_t j = i + 1;
    int digits = 0;
    if (j < pattern.size() && pattern[j] == '0' && j + 1 < pattern.size() && pattern[j + 1] >= '1' &&
        pattern[j + 1] <= '9') {
      digits = pattern[j + 1] - '0';
      j += 2;
    }
    if (j >= pattern.size() || pattern[j] != 'd' || found)
      throw Error(option + " " + pattern +
                  ": a frame sequence's name holds one frame number, %d or %0Nd (N at most "
                  "9; %% for a percent sign), as in frames/%04d.exr");
    found = true;
    digits_ = digits;
    part = &suffix_;
    i = j;
  }
  if (!found)
    throw Error(option + " " + pattern +
                ": a frame sequence's name holds one frame number, %d or %0Nd, as in "
                "frames/%04d.exr");
}

std::string FramePattern::path(long long frame) const {
  std::string number = std::to_string(frame < 0 ? -frame : frame);
  if (number.size() < size_t(digits_)) number.insert(0, size_t(digits_) - number.size(), '0');
  return prefix_ + (frame < 0 ? "-" : "") + number + suffix_;
}

}  // namespace rcsplat
