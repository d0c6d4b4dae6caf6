#!/usr/bin/env bash
# Intel Open Image Denoise for `rcsplat render --denoise`: Debian 12 has no package, so this takes the libraries from
# PyPI's pyoidn wheel (which ships them, without headers) and keeps only what rcsplat loads at run time: the library,
# its core, the CPU and CUDA devices and TBB, in DIR/lib (default build/oidn/lib, where rcsplat looks first; the
# libraries find each other through their own $ORIGIN/../lib). rcsplat builds and runs without them: a failure here
# (no network, no pip) is a warning, and `--denoise` then says what is missing. Idempotent.
#   bash scripts/install-oidn.sh [DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-build/oidn}"
version=2.5.1.0  # OIDN 2.5.1; the C API rcsplat declares (host/image/denoiser.cpp) is OIDN 2's
want=(libOpenImageDenoise.so.2 libOpenImageDenoise_core.so.2.5.1 libOpenImageDenoise_device_cpu.so.2.5.1
      libOpenImageDenoise_device_cuda.so.2.5.1 libtbb.so.12)
have_all=1
for lib in "${want[@]}"; do [ -f "$dir/lib/$lib" ] || have_all=0; done
if [ "$have_all" = 1 ]; then
  echo "install-oidn: Open Image Denoise already in $dir/lib"
  exit 0
fi
if ! python3 -m pip --version > /dev/null 2>&1 || ! command -v unzip > /dev/null; then
  echo "install-oidn: WARNING: needs pip and unzip (scripts/install-debian-packages.sh installs them);" \
    "rcsplat works without Open Image Denoise, but --denoise will not" >&2
  exit 0
fi
download="$(mktemp -d)"
trap 'rm -rf "$download"' EXIT
if ! python3 -m pip download -q --no-deps --only-binary=:all: --platform manylinux2014_x86_64 \
    "pyoidn==$version" -d "$download"; then
  echo "install-oidn: WARNING: could not download pyoidn $version from PyPI; rcsplat works without it," \
    "but --denoise will not" >&2
  exit 0
fi
mkdir -p "$dir/lib"
for lib in "${want[@]}"; do
  unzip -o -q -j "$download"/pyoidn-*.whl "pyoidn/oidn/lib/$lib" -d "$dir/lib"
done
echo "install-oidn: Open Image Denoise $version in $dir/lib"
