#!/usr/bin/env bash
# Runs the whole test suite (GoogleTest through CTest) on the default OpenCL device: PoCL's CPU device here. Then, as
# CI does, the host code's suites again under AddressSanitizer and UndefinedBehaviorSanitizer (scripts/sanitize.sh, which
# says which and why) and half a minute of fuzzing of scene loading (scripts/fuzz.sh; every seed, the hostile scenes'
# included, runs first; `bash scripts/fuzz.sh 600` fuzzes longer), and the render-farm scripts on a one-node Slurm
# cluster started on this machine (tests/slurm/run_test.sh; as root). --quick runs the suite alone. Each
# part prints its time: the whole is meant to stay within 12 minutes on 2 cores (docs/NOTES.md, "CI time").
set -euo pipefail
cd "$(dirname "$0")/.."
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
timed() {
  local start=$SECONDS
  "$@"
  echo "test.sh: '$*' took $((SECONDS - start)) s"
}
timed cmake --build build -j "$(nproc)"
timed ctest --test-dir build --output-on-failure -j "$(nproc)"
if [ "${1:-}" != "--quick" ]; then
  timed bash scripts/sanitize.sh
  timed bash scripts/fuzz.sh 30
  if [ "$(id -u)" -eq 0 ]; then
    timed bash tests/slurm/run_test.sh
  else
    echo "test.sh: the Slurm test was not run: its node daemon starts jobs as their users, so it needs root" \
      "(sudo bash tests/slurm/run_test.sh)"
  fi
fi
