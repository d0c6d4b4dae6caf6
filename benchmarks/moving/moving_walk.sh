#!/usr/bin/env bash
# Issue 62 item 4: an animated scene (benchmarks/make_moving_scenes.py writes the held-out ones) played by its still
# camera for LAST_FRAME + 1 frames at 24 frames/s, four ways: records kept through the moves (`animate`'s default), a
# cache per frame (--cache-per-frame: the scene loaded again in each frame's pose, every record placed anew, the
# photon map shot again), stratified path tracing at PATH_SPP samples plus OIDN (benchmarks/denoise.py), and converged
# references (REF_SPP path samples, 16 pixel samples) at the judged frames. Then error per judged frame (rcsplat
# compare), the ghost metric (benchmarks/moving/ghosts.py: error over the pixels the motion changed), flicker
# (rcsplat flicker over each sequence) and time a frame (benchmarks/moving/summary.py).
#   benchmarks/moving/moving_walk.sh SCENE.gltf OUT_DIR [render|analyse|all]
# Needs build/rcsplat and, for OIDN and the analysis, benchmarks/.venv (bash benchmarks/setup_python.sh).
set -euo pipefail
scene="$(realpath "$1")"
out="$2"
stage="${3:-all}"
here="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${RCSPLAT:-$here/build/rcsplat}"
py="$here/benchmarks/.venv/bin/python"
width="${WIDTH:-320}"
height="${HEIGHT:-240}"
last="${LAST_FRAME:-119}"
path_spp="${PATH_SPP:-4}"
ref_spp="${REF_SPP:-1024}"
read -r -a judged <<<"${JUDGED:-30 60 119}"
read -r -a kept_options <<<"${KEPT_OPTIONS:-}"
common=(animate "$scene" --width "$width" --height "$height" --last-frame "$last")
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$here/build/pocl-cache}"
mkdir -p "$out"/{kept,fresh,path,oidn,ref}

if [ "$stage" = render ] || [ "$stage" = all ]; then
  "$bin" "${common[@]}" "${kept_options[@]}" -o "$out/kept/%04d.exr" -o "$out/kept/%04d.png" \
    --stats "$out/kept.csv" --json "$out/kept.json" --mp4 "$out/kept.mp4"
  "$bin" "${common[@]}" --cache-per-frame -o "$out/fresh/%04d.exr" -o "$out/fresh/%04d.png" \
    --stats "$out/fresh.csv" --json "$out/fresh.json" --mp4 "$out/fresh.mp4"
  "$bin" "${common[@]}" --gi path --spp "$path_spp" --stratified -o "$out/path/%04d.exr" --stats "$out/path.csv"
  for exr in "$out"/path/*.exr; do
    name="$(basename "$exr" .exr)"
    "$py" "$here/benchmarks/denoise.py" "$exr" "$out/oidn/$name.exr" --json "$out/oidn/$name.json" > /dev/null
  done
  for f in "${judged[@]}"; do
    [ "$f" -le "$last" ] || continue
    "$bin" animate "$scene" --width "$width" --height "$height" --first-frame "$f" --last-frame "$f" \
      --gi path --spp "$ref_spp" --stratified --light-samples 256 --pixel-samples 16 -o "$out/ref/%04d.exr"
  done
fi

if [ "$stage" = analyse ] || [ "$stage" = all ]; then
  for f in "${judged[@]}"; do
    [ "$f" -le "$last" ] || continue
    n="$(printf %04d "$f")"
    for m in kept fresh oidn; do
      "$bin" compare "$out/$m/$n.exr" "$out/ref/$n.exr" --json "$out/compare_${m}_$n.json" > "$out/compare_${m}_$n.txt"
    done
  done
  "$bin" flicker "$out/kept/%04d.exr" --json "$out/flicker_kept.json"
  "$bin" flicker "$out/fresh/%04d.exr" --json "$out/flicker_fresh.json"
  "$bin" flicker "$out/oidn/%04d.exr" --positions "$out/path/%04d.exr" --json "$out/flicker_oidn.json"
  "$py" "$here/benchmarks/moving/ghosts.py" "$out" "${judged[@]}" > "$out/ghosts.txt"
  "$py" "$here/benchmarks/moving/summary.py" "$out" | tee "$out/summary.txt"
fi
