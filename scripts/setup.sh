#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a rendered image: installs the packages rcsplat needs, builds it
# (Release, binary at build/rcsplat) and renders the built-in Cornell box to cornell.exr and cornell.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-debian-packages.sh
bash scripts/install-oidn.sh  # optional: --denoise's library; a warning where it cannot be had
# PoCL reports no device at all when its kernel cache is not writable: give it one unless the caller did.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
build/rcsplat render -o cornell.exr -o cornell.png --json cornell.json
