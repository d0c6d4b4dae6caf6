#!/usr/bin/env bash
# Issue 59 item 1 on several scenes: for each, a path-traced reference (SPP samples, default 1024), the cache at the
# render defaults, and benchmarks/firefly_share.py (pixels brighter than 10 x the reference + 1, their share of the
# per-pixel relMSE, the brightest 0.1%'s share). Writes OUT/NAME.{ref,cache}.exr and prints one line a scene.
#   SPP=1024 bash benchmarks/fireflies_scenes.sh OUT W H SCENE...
set -euo pipefail
cd "$(dirname "$0")/.."
out="$1" width="$2" height="$3"
shift 3
spp="${SPP:-1024}"
mkdir -p "$out"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
for scene in "$@"; do
  name="$(basename "${scene%.gltf}")"
  build/rcsplat reference "$scene" --width "$width" --height "$height" --spp "$spp" -o "$out/$name.ref.exr" > /dev/null 2>&1
  build/rcsplat render "$scene" --width "$width" --height "$height" -o "$out/$name.cache.exr" > /dev/null 2>&1
  echo "== $name ($width x $height, reference $spp spp)"
  benchmarks/.venv/bin/python benchmarks/firefly_share.py "$out/$name.cache.exr" "$out/$name.ref.exr"
done
