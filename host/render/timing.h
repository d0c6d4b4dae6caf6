// Wall-clock timing of the passes, for the summary.
#pragma once
#include <chrono>

namespace rcsplat {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace rcsplat
