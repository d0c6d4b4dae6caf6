// Wall-clock timing of the passes, for the summary.
#pragma once
#include <chrono>

namespace rcsplat {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Adds the seconds from its construction to the end of its scope (or to stop()) to one of RenderStats' stage times:
//   { StageTimer timing(st.irradiance.splat_s); splat.splat_all(...); }
class StageTimer {
 public:
  explicit StageTimer(double& stage_seconds) : stage_seconds_(stage_seconds), start_(Clock::now()) {}
  ~StageTimer() { stop(); }
  void stop() {
    if (running_) stage_seconds_ += seconds_since(start_);
    running_ = false;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  double& stage_seconds_;
  Clock::time_point start_;
  bool running_ = true;
};

}  // namespace rcsplat
