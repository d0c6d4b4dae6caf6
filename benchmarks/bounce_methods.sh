#!/usr/bin/env bash
# How a record's ray finds the bounces after the first (issue 11 part 3): path continuation against photon-map final
# gathering, on Sponza and Sibenik at 512 x 384 for N = 2 and 3 (N = 1 as the anchor), each render run RUNS times,
# interleaved; errors of the indirect layer against path-traced references of REFERENCE_SPP samples with the same N
# (written to OUT_DIR unless there already). Prints one table row per render: median seconds of the records, the
# photon map and the frame (less BVH build, upload and kernel build), record rays, mean indirect and the errors.
# Usage: benchmarks/bounce_methods.sh OUT_DIR [RUNS] [REFERENCE_SPP]   (needs ../shared/scenes and build/rcsplat)
set -euo pipefail
out=${1:?output directory}
runs=${2:-3}
spp=${3:-1024}
here=$(cd "$(dirname "$0")/.." && pwd)
rcsplat=$here/build/rcsplat
scenes=$here/../shared/scenes
mkdir -p "$out"
frame=(--width 512 --height 384 --pixel-samples 1)  # as measured (the default is now 4)
for scene in sponza_dabrovic/sponza sibenik/sibenik_textured; do
  name=$(basename "$scene")
  for n in 1 2 3; do
    ref=$out/${name}_ref_b$n.exr
    [ -f "$ref" ] || "$rcsplat" reference "$scenes/$scene.gltf" "${frame[@]}" --bounces "$n" --spp "$spp" -o "$ref" -q > /dev/null
  done
  for run in $(seq "$runs"); do
    for config in "1 path" "2 path" "2 photons" "3 path" "3 photons"; do
      set -- $config
      "$rcsplat" render "$scenes/$scene.gltf" "${frame[@]}" --bounces "$1" --bounce-method "$2" \
        -o "$out/${name}_b$1_$2.exr" --json "$out/${name}_b$1_$2_run$run.json" -q > /dev/null
    done
  done
  for config in "1 path" "2 path" "2 photons" "3 path" "3 photons"; do
    set -- $config
    ref=$out/${name}_ref_b$1.exr
    errors=$("$rcsplat" compare "$out/${name}_b$1_$2.exr" "$ref" --json "$out/${name}_b$1_$2_compare.json" -q > /dev/null
      python3 - "$out/${name}_b$1_$2_compare.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
ind = j["indirect"]
print(f'{ind["rel_mse_less_reference_noise"]:.3g} {ind["block_rel_mse_less_reference_noise"]:.3g}')
PY
    )
    python3 - "$name" "$1" "$2" "$errors" "$out/${name}_b$1_$2_run"*.json <<'PY'
import json, statistics, sys
name, n, method, errors = sys.argv[1:5]
runs = [json.load(open(p)) for p in sys.argv[5:]]
def median(f): return statistics.median(f(j) for j in runs)
s = lambda j: j["seconds"]
frame = median(lambda j: s(j)["total"] - s(j)["bvh_build"] - s(j)["upload"] - s(j)["kernel_build"])
records = median(lambda j: s(j)["records"])
photons = median(lambda j: j["cache"]["later_bounces"]["seconds"])
j = runs[0]
print(f'| {name} | {n} | {method} | {records:.2f} | {photons:.2f} | {frame:.2f} | {j["rays"]["records"]:,} | {errors.split()[0]} | {errors.split()[1]} |')
PY
  done
done
