#!/usr/bin/env bash
# Renders a fixed set of small frames (every indirect method, anti-aliasing on and off, a sky, radiance-cached
# lobes, a textured scene) with one rcsplat binary into a folder, or, given a second folder, checks that another
# binary's frames are the same bits: the full and indirect layers' RMSE and MAE against the first must be exactly 0. For
# refactors that promise unchanged images (issue 40's renderer object). Needs ../shared/scenes for two cases
# (skipped without it).
#   benchmarks/same_images.sh BINARY OUT_DIR [BASELINE_DIR]
set -euo pipefail
binary="$1" out="$2" baseline="${3:-}"
scenes="$(cd "$(dirname "$0")/../.." && pwd)/shared/scenes"
mkdir -p "$out"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
cases=(
  "cornell_splat||--width 128 --height 128"
  "cornell_octree||--width 96 --height 96 --gi octree"
  "cornell_path||--width 96 --height 96 --gi path --spp 16"
  "cornell_path_grid||--width 96 --height 96 --gi path --spp 16 --sub-pixel-grid"
  "cornell_none||--width 96 --height 96 --gi none"
  "cornell_sky||--width 96 --height 96 --sky 0.3,0.4,0.6"
  "cornell_one_sample_path_bounces||--width 96 --height 96 --pixel-samples 1 --bounces 3 --bounce-method path"
  "glossy_splat|cornell_box_mcguire/CornellBox-Glossy.gltf|--width 128 --height 128"
  "glossy_path|cornell_box_mcguire/CornellBox-Glossy.gltf|--width 96 --height 96 --gi path --spp 16"
  "sponza_splat|sponza_dabrovic/sponza.gltf|--width 160 --height 120"
)
failed=0
for c in "${cases[@]}"; do
  IFS='|' read -r name scene args <<<"$c"
  if [ -n "$scene" ]; then
    [ -f "$scenes/$scene" ] || { echo "$name: skipped (no $scenes/$scene)"; continue; }
    scene="$scenes/$scene"
  fi
  # shellcheck disable=SC2086
  "$binary" render $scene $args -o "$out/$name.exr" --json "$out/$name.json" > "$out/$name.log" 2>&1 ||
    { echo "$name: render failed (see $out/$name.log)"; failed=1; continue; }
  if [ -n "$baseline" ]; then
    "$binary" compare "$out/$name.exr" "$baseline/$name.exr" --json "$out/$name.compare.json" > /dev/null
    if python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if all(d[l]["rmse"]==0 and d[l]["mae"]==0 for l in ("full","indirect") if l in d) else 1)' \
        "$out/$name.compare.json"; then echo "$name: same bits"; else echo "$name: DIFFERENT"; failed=1; fi
  else
    echo "$name: rendered"
  fi
done
exit $failed
