// Shared helpers for the tests: one OpenCL context for the whole run, and scratch files.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "cl/gpu_context.h"
#include "render/settings.h"

namespace rcsplat::test {

// The device tests run on: RCSPLAT_TEST_DEVICE (index or name) or the default choice (PoCL's CPU device in CI).
GpuContext& gpu();
// A context of its own on the same device, for a test that reads what a context built and launched (the suite runs
// in a few processes, so the shared one holds other tests' programs).
std::unique_ptr<GpuContext> fresh_gpu();

// A fresh scratch directory for this test, removed at exit.
std::string scratch_dir();

void write_file(const std::string& path, const std::string& content);

// The rcsplat binary the suite was built with, run in `folder` with `args` as a user runs it: its exit code (128 +
// the signal when killed), its stdout and stderr together, and its peak resident memory. A run past limit_seconds is
// killed and fails the test (a hang is a failure, not a measurement). Tests of a command go through this, never
// through the command line's code.
struct CommandRun {
  int exit_code = -1;
  std::string output;
  long peak_memory_kib = 0;
};
CommandRun run_rcsplat(const std::string& folder, const std::vector<std::string>& args, int limit_seconds = 300);

// A request for one bounce and one sample a pixel, what most tests isolate; the library's own defaults (0: chosen
// from the scene, as on the command line) are tested where a test says so.
inline RenderSettings one_bounce_one_sample() {
  RenderSettings s;
  s.bounces = 1;
  s.pixel_samples = 1;
  return s;
}

}  // namespace rcsplat::test
