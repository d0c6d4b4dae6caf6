#!/usr/bin/env bash
# The host code under AddressSanitizer and UndefinedBehaviorSanitizer (build-asan/): the suites whose host side is
# not already the plain run's alone to check. The kernels run in PoCL, which is not instrumented, so the suites that
# test kernel numerics (convergence, records against double precision, BRDF sampling, hard cases) would mostly repeat
# the plain run; their host side (the renderer, every pass's buffers, the layers, the photon map's and the guide's
# host builds) runs here through the Renderer, Leaks, Determinism, KernelArgs, PhotonMap and LightGuide suites, and
# every file the loader reads through GltfLoader and GltfConformance. The hostile files of tests/untrusted_scenes.cpp
# run under both sanitizers as the fuzzer's seeds (scripts/fuzz.sh), so their suite (which starts the binary 42 times)
# is left to the plain run and not built here; so are the photon map's estimates against double-precision sums (kernel numerics whose
# host references take half a minute under ASan). --all runs every suite. Any report fails the test that triggered it.
set -euo pipefail
cd "$(dirname "$0")/.."
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# -O0 -g1: line tables for the reports at the least compile time (measured 2026-12-07 on 2 cores: -O1 built in about
# 200 s and ran the suites in 77 s, -O0 in 121 s and 91 s; the kernels run in PoCL either way); the library as a unity build
# (16 files a unit; the tests stay one unit a file, tests/CMakeLists.txt): about a minute less on 2 cores. Every layer
# in one library (RCSPLAT_LAYER_LIBRARIES=OFF): 7 units, not 13 (one a layer at least); the plain build keeps the
# layers' fence. The suite
# runs in shards, as the plain run does (a process's start under ASan is about 1.4 s: one per test was a minute and a
# half of the CI's test command); a report fails its shard, whose output names the test. --all runs every suite, one
# process a test.
# The files that test kernel numerics alone are not built here (RCSPLAT_TEST_KERNEL_NUMERICS, tests/CMakeLists.txt);
# these are the kernel-numerics suites in files shared with host-side ones.
kernel_numerics='HardCases.*:SubPixelSides/LayerPassTest.*:Bench.*:PhotonMap.EstimatesMatchADoublePrecisionSumOverTheDisc'
kernel_numerics+=':PhotonMap.EstimatesWithTheSceneSurface*'
# Walkthroughs of a moving scene (tests/moving_scene_test.cpp): kernels mostly; the moving BVH's refit, the animator and
# the records' marks run here through MovingBvh, SceneAnimator and KeptRecords.
kernel_numerics+=':MovingScene.*'
# Open Image Denoise is not instrumented either (a prebuilt library with TBB's threads): its suite runs in the plain run.
kernel_numerics+=':OpenImageDenoise.*'
# Kernels against the path tracer, and every kernel's arguments built afresh (a GpuContext of its own compiles all of
# them: 13 s of PoCL, not instrumented); the caustic map's host build and the binding by name run here through
# PhotonMap, Renderer and every frame (measured 2026-12-07 under ASan: 26 s of the suites' 210 CPU-seconds).
kernel_numerics+=':CausticMap.Glossy*:KernelArgs.EveryKernelIsBoundByNameInItsOwnOrder'
if [ "${1:-}" = "--all" ]; then
  layout=(-DRCSPLAT_TEST_PER_PROCESS=ON -DRCSPLAT_TEST_KERNEL_NUMERICS=ON)
else
  layout=(-DRCSPLAT_TEST_PER_PROCESS=OFF -DRCSPLAT_TEST_KERNEL_NUMERICS=OFF "-DRCSPLAT_TEST_SKIP=$kernel_numerics"
          -DRCSPLAT_TEST_UNTRUSTED=OFF)
fi
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O0 -g1" \
  -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 -DRCSPLAT_LAYER_LIBRARIES=OFF -DRCSPLAT_SANITIZE=ON \
  -DRCSPLAT_BUILD_BENCHMARKS=OFF \
  "${layout[@]}" > /dev/null
cmake --build build-asan -j "$(nproc)" --target rcsplat rcsplat_tests
ctest --test-dir build-asan --output-on-failure -j "$(nproc)"
