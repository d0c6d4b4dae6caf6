#!/usr/bin/env bash
# Kernel build time per switch set (issue 11 part 2): each scene renders an 8 x 8 image twice, first with empty kernel
# caches (rcsplat's and PoCL's: cold), then with the caches the first run filled (cached). Prints the scene's switches
# (rcsplat info) and both kernel-build times from the render's JSON summary.
#   benchmarks/switch_build_times.sh [RCSPLAT] [SCENE ...]
# Default scenes: the built-in Cornell box and, when ../shared/scenes is there, CornellBox-Glossy, Sponza, Sibenik.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
rcsplat=${1:-$here/build/rcsplat}
shift || true
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=("")
  shared=$here/../shared/scenes
  for s in cornell_box_mcguire/CornellBox-Glossy.gltf sponza_dabrovic/sponza.gltf sibenik/sibenik_textured.gltf; do
    [ -f "$shared/$s" ] && scenes+=("$shared/$s")
  done
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-28s %-9s %-9s %s\n' scene cold_s cached_s switches
for scene in "${scenes[@]}"; do
  name=${scene:-built-in Cornell box}
  rm -rf "$work/cache" "$work/pocl"
  times=()
  for run in cold cached; do
    RCSPLAT_CACHE_DIR=$work/cache POCL_CACHE_DIR=$work/pocl "$rcsplat" render -q $scene --width 8 --height 8 \
      -o "$work/out.exr" --json "$work/$run.json" > /dev/null 2>&1
    times+=("$(python3 -c "import json,sys; print('%.3f' % json.load(open(sys.argv[1]))['seconds']['kernel_build'])" "$work/$run.json")")
  done
  switches=$(python3 -c "import json,sys; d=json.load(open(sys.argv[1]))['scene_plan']['switches']; print(' '.join(k.replace('HAS_','')+'='+v for k,v in sorted(d.items())))" "$work/cold.json")
  printf '%-28s %-9s %-9s %s\n' "$(basename "$name")" "${times[0]}" "${times[1]}" "$switches"
done
