#!/usr/bin/env bash
# Sponza under a uniform sky and under a sun-and-sky map (benchmarks/make_sky.py): the cache at default settings
# against stratified path tracing, each against a converged reference (issue 11 part 4).
# Usage: benchmarks/environment_sponza.sh OUT_DIR [REFERENCE_SPP]   (needs ../shared/scenes and build/rcsplat)
set -euo pipefail
out=${1:?output directory}
spp=${2:-512}
here=$(cd "$(dirname "$0")/.." && pwd)
rcsplat=$here/build/rcsplat
scene=$here/../shared/scenes/sponza_dabrovic/sponza.gltf
mkdir -p "$out"
python3 "$here/benchmarks/make_sky.py" "$out/sun_sky.hdr" --width 512 --sun-elevation 65 --sun-azimuth 90 --sun 8000
frame=(--width 512 --height 384 --bounces 1 --pixel-samples 1)  # as measured (defaults are now chosen)
for light in "sky --sky 0.6,0.7,0.9" "sun --environment $out/sun_sky.hdr"; do
  name=${light%% *}
  args=(${light#* })
  "$rcsplat" reference "$scene" "${frame[@]}" "${args[@]}" --spp "$spp" -o "$out/${name}_ref.exr" -q > /dev/null
  "$rcsplat" render "$scene" "${frame[@]}" "${args[@]}" -o "$out/${name}_cache.exr" -o "$out/${name}_cache.png" \
    --json "$out/${name}_cache.json" -q > /dev/null
  for path_spp in 16 64; do
    "$rcsplat" render "$scene" "${frame[@]}" "${args[@]}" --gi path --stratified --spp "$path_spp" \
      -o "$out/${name}_path$path_spp.exr" --json "$out/${name}_path$path_spp.json" -q > /dev/null
  done
  for image in cache path16 path64; do
    seconds=$(python3 -c "import json,sys; j=json.load(open(sys.argv[1]))['seconds']; print(round(j['total'] - j['bvh_build'] - j['upload'] - j['kernel_build'], 3))" "$out/${name}_$image.json")
    echo "== $name $image: $seconds s (frame, less BVH build, upload and kernel build)"
    "$rcsplat" compare "$out/${name}_$image.exr" "$out/${name}_ref.exr"
  done
done
