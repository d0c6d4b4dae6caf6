// Shared helpers for the tests: one OpenCL context for the whole run, and scratch files.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

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

// A request for one bounce and one sample a pixel, what most tests isolate; the library's own defaults (0: chosen
// from the scene, as on the command line) are tested where a test says so.
inline RenderSettings one_bounce_one_sample() {
  RenderSettings s;
  s.bounces = 1;
  s.pixel_samples = 1;
  return s;
}

}  // namespace rcsplat::test
