#!/usr/bin/env bash
# Packs what a bare GPU machine needs to run rcsplat's OpenCL path into .gpu/ (ignored by git; carried by the device
# tool): a build without OpenImageIO (its codec libraries weigh 390 MB), the shared libraries that build links beyond
# glibc and libstdc++, an OpenCL ICD loader and clinfo from Debian, and the benchmark scenes. docs/GPU.md says how it is
# used.   benchmarks/gpu/bundle.sh [BUILD_DIR]   (default /tmp/rcsplat-lean)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-/tmp/rcsplat-lean}
scenes=${RCSPLAT_SCENES:-$root/../shared/scenes}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRCSPLAT_WITH_OPENIMAGEIO=OFF \
  -DRCSPLAT_BUILD_TESTS=OFF -DRCSPLAT_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target rcsplat >/dev/null
bundle=$root/.gpu
rm -rf "$bundle" && mkdir -p "$bundle/lib" "$bundle/scenes"
cp "$build/rcsplat" "$bundle/"
# The loader, libc, libm and the C++ runtime are the GPU machine's own (newer, backward compatible).
ldd "$build/rcsplat" | awk '$3 ~ /^\// {print $3}' |
  grep -vE '/(libc|libm|libpthread|libdl|librt|ld-linux[^/]*|libstdc\+\+|libgcc_s)\.so' |
  xargs -I{} cp -L {} "$bundle/lib/"
tar -C "$bundle" -cJf "$bundle/lib.tar.xz" lib && rm -rf "$bundle/lib"
(cd "$bundle" && apt-get download ocl-icd-libopencl1 clinfo >/dev/null 2>&1)
for s in sponza_dabrovic sibenik; do cp -r "$scenes/$s" "$bundle/scenes/"; done
du -sh "$bundle"
