#!/usr/bin/env bash
# Issue 42's walkthrough measurement: benchmarks/walkthrough/sponza_walk.txt through Sponza (512 x 384, render
# defaults) rendered with records kept across frames (the default), with a cache per frame (--cache-per-frame), and by
# stratified path tracing plus OIDN; then the walk again from the kept run's final cache file (--cache-in: a frozen
# cache that places nothing, whose flicker is the floor that reprojection to the nearest pixel leaves: the flicker of
# a renderer whose light does not change); references at frames 0, 60 and 119; then error per frame against the
# references, flicker of each sequence (rcsplat flicker), and a plot of time and flicker per frame (walk.png).
#   benchmarks/walkthrough/sponza_walk.sh OUT_DIR [render|analyse|all]   (needs ../shared/scenes, build/rcsplat and,
#   for OIDN and the plot, benchmarks/setup_python.sh's environment; RCSPLAT=path/to/binary to use another binary;
#   SCENE, CAMERA_PATH (the path's options) and TITLE walk another scene: benchmarks/walkthrough/glossy_orbit.sh)
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
out="$1" stage="${2:-all}"
bin="${RCSPLAT:-$here/build/rcsplat}"
py="$here/benchmarks/.venv/bin/python"
scene="${SCENE:-$here/../shared/scenes/sponza_dabrovic/sponza.gltf}"
read -r -a camera_path <<<"${CAMERA_PATH:---keyframes $here/benchmarks/walkthrough/sponza_walk.txt}"
title="${TITLE:-Sponza walk, 512 x 384}"
last="${LAST_FRAME:-119}"
path_spp="${PATH_SPP:-4}"
references=(0 60 119)
common=(animate "$scene" "${camera_path[@]}" --width 512 --height 384 --last-frame "$last")
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$here/build/pocl-cache}"
mkdir -p "$out"/{kept,frozen,fresh,path,oidn,ref}

if [ "$stage" = render ] || [ "$stage" = all ]; then
  "$bin" "${common[@]}" -o "$out/kept/%04d.exr" -o "$out/kept/%04d.png" --stats "$out/kept.csv" \
    --json "$out/kept.json" --mp4 "$out/kept.mp4" --cache-out "$out/walk.cache"
  "$bin" "${common[@]}" -o "$out/frozen/%04d.exr" --stats "$out/frozen.csv" --cache-in "$out/walk.cache"
  for f in "${references[@]}"; do
    [ "$f" -le "$last" ] || continue
    "$bin" animate "$scene" "${camera_path[@]}" --width 512 --height 384 --first-frame "$f" --last-frame "$f" \
      --gi path --spp 256 --stratified --light-samples 256 --pixel-samples 16 -o "$out/ref/%04d.exr"
  done
  "$bin" "${common[@]}" --gi path --spp "$path_spp" --stratified -o "$out/path/%04d.exr" --stats "$out/path.csv"
  for exr in "$out"/path/*.exr; do
    name="$(basename "$exr" .exr)"
    "$py" "$here/benchmarks/denoise.py" "$exr" "$out/oidn/$name.exr" --json "$out/oidn/$name.json" > /dev/null
  done
  "$bin" "${common[@]}" --cache-per-frame -o "$out/fresh/%04d.exr" -o "$out/fresh/%04d.png" --stats "$out/fresh.csv" \
    --json "$out/fresh.json" --mp4 "$out/fresh.mp4"
fi

if [ "$stage" = analyse ] || [ "$stage" = all ]; then
  for f in "${references[@]}"; do
    [ "$f" -le "$last" ] || continue
    n="$(printf %04d "$f")"
    for m in kept fresh oidn; do
      "$bin" compare "$out/$m/$n.exr" "$out/ref/$n.exr" --json "$out/compare_${m}_$n.json" > "$out/compare_${m}_$n.txt"
    done
  done
  for over in "" --demodulate; do
    suffix="${over:+_demodulated}"
    "$bin" flicker "$out/kept/%04d.exr" $over --json "$out/flicker_kept$suffix.json"
    "$bin" flicker "$out/frozen/%04d.exr" $over --json "$out/flicker_frozen$suffix.json"
    "$bin" flicker "$out/fresh/%04d.exr" $over --json "$out/flicker_fresh$suffix.json"
    "$bin" flicker "$out/oidn/%04d.exr" --positions "$out/path/%04d.exr" $over --json "$out/flicker_oidn$suffix.json"
  done
  "$py" "$here/benchmarks/walkthrough/plot_walk.py" "$out" "$title"
fi
