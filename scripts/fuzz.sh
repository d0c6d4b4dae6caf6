#!/usr/bin/env bash
# Fuzzes scene loading and validation (tests/fuzz/scene_loader_fuzzer.cpp) with libFuzzer for SECONDS (default 60),
# starting from tests/fuzz/corpus and the hostile scenes of tests/untrusted_scenes.cpp (written by
# write_untrusted_corpus), every seed first run once under AddressSanitizer and UndefinedBehaviorSanitizer. Builds
# build-fuzz/ with clang. A finding is written to build-fuzz/findings/ and
# the script exits non-zero; add the file to the corpus once it is fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DRCSPLAT_BUILD_FUZZER=ON \
  -DRCSPLAT_BUILD_TESTS=OFF -DRCSPLAT_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_scene_loader write_untrusted_corpus
mkdir -p build-fuzz/work build-fuzz/findings
rm -rf build-fuzz/untrusted && build-fuzz/write_untrusted_corpus build-fuzz/untrusted
# The loader's warnings go to stderr for every input: keep only libFuzzer's own lines and the report.
build-fuzz/fuzz_scene_loader -max_total_time="$seconds" -max_len=16384 -dict=tests/fuzz/gltf.dict \
  -artifact_prefix=build-fuzz/findings/ -print_final_stats=1 build-fuzz/work tests/fuzz/corpus build-fuzz/untrusted 2>&1 |
  grep -v '^warning: ' | tail -40
