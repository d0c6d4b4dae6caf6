#!/usr/bin/env bash
# Runs the whole test suite (GoogleTest through CTest) on the default OpenCL device: PoCL's CPU device here. Then, as
# CI does, the suite again under AddressSanitizer and UndefinedBehaviorSanitizer (scripts/sanitize.sh) and a minute of
# fuzzing of scene loading (scripts/fuzz.sh). --quick runs the suite alone.
set -euo pipefail
cd "$(dirname "$0")/.."
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
cmake --build build -j "$(nproc)"
ctest --test-dir build --output-on-failure -j "$(nproc)"
if [ "${1:-}" != "--quick" ]; then
  bash scripts/sanitize.sh
  bash scripts/fuzz.sh 60
fi
