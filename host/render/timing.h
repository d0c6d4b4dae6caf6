// Wall-clock timing of a frame's stages, for the summary: one scoped timer for every stage.
#pragma once
#include <chrono>

#include "cl/gpu_context.h"

namespace rcsplat {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Adds the seconds from its construction to the end of its scope (or to stop()) to a stage's time in RenderStats:
//   { StageTimer timing(st.irradiance.splat_s); splat.splat_all(...); }
// Given the GPU context, the kernel builds inside the scope are left out of the stage (a cold build on a GPU is
// seconds: it would swamp the stage), and given the frame's program_s too, they are added there. A stage timed inside
// another gives only the context: the outer timer counts the builds once.
class StageTimer {
 public:
  explicit StageTimer(double& stage_seconds) : StageTimer(stage_seconds, nullptr, nullptr) {}
  StageTimer(double& stage_seconds, const GpuContext& gpu) : StageTimer(stage_seconds, &gpu, nullptr) {}
  StageTimer(double& stage_seconds, const GpuContext& gpu, double& program_seconds)
      : StageTimer(stage_seconds, &gpu, &program_seconds) {}
  ~StageTimer() { stop(); }
  void stop() {
    if (!running_) return;
    running_ = false;
    const double builds = gpu_ ? gpu_->program_seconds() - builds_before_ : 0.0;
    stage_seconds_ += seconds_since(start_) - builds;
    if (program_seconds_) *program_seconds_ += builds;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageTimer(double& stage_seconds, const GpuContext* gpu, double* program_seconds)
      : stage_seconds_(stage_seconds),
        gpu_(gpu),
        program_seconds_(program_seconds),
        start_(Clock::now()),
        builds_before_(gpu ? gpu->program_seconds() : 0.0) {}

  double& stage_seconds_;
  const GpuContext* gpu_;
  double* program_seconds_;
  Clock::time_point start_;
  double builds_before_;
  bool running_ = true;
};

// Adds the kernel builds from its construction to the end of its scope (or to stop()) to the frame's program_s: where
// passes are made (their programs built, or read from the caches) outside any stage.
class BuildTimer {
 public:
  BuildTimer(const GpuContext& gpu, double& program_seconds) : timer_(ignored_, gpu, program_seconds) {}
  void stop() { timer_.stop(); }

 private:
  double ignored_ = 0.0;  // the wall time, which the stage around counts
  StageTimer timer_;
};

}  // namespace rcsplat
