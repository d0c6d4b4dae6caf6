// The one exception type rcsplat throws for conditions a user can cause (bad input, no usable device, I/O):
// the CLI prints its message and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace rcsplat {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace rcsplat
