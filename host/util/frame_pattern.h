// File names of a frame sequence: "frames/%04d.exr" holds one frame-number field (%d, or %0Nd padded to N digits,
// N at most 9), and %% stands for a percent sign, as ffmpeg reads the same pattern.
#pragma once
#include <string>

namespace rcsplat {

class FramePattern {
 public:
  // Throws rcsplat::Error naming `option` and the pattern when it has no frame-number field, more than one, or a
  // percent sign that is neither.
  FramePattern(const std::string& pattern, const std::string& option);
  std::string path(long long frame) const;
  const std::string& pattern() const { return pattern_; }

 private:
  std::string pattern_, prefix_, suffix_;
  int digits_ = 0;
};

}  // namespace rcsplat
