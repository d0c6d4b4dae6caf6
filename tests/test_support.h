// Shared helpers for the tests: one OpenCL context for the whole run, and scratch files.
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "cl/gpu_context.h"

namespace rcsplat::test {

// The device tests run on: RCSPLAT_TEST_DEVICE (index or name) or the default choice (PoCL's CPU device in CI).
GpuContext& gpu();

// A fresh scratch directory for this test, removed at exit.
std::string scratch_dir();

void write_file(const std::string& path, const std::string& content);

}  // namespace rcsplat::test
