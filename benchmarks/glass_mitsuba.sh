#!/usr/bin/env bash
# Issue 61 item 4: rcsplat's glass against Mitsuba 3's (thindielectric, dielectric) on the small scenes of
# benchmarks/make_glass_panes.py under a uniform sky: each scene's converged rcsplat reference against Mitsuba's
# converged render, mean ratio per channel over the image (benchmarks/mitsuba_peer.py's agreement). The floor alone is
# the control. Writes OUT/table.md.
#   bash benchmarks/setup_python.sh   # once
#   SIZE=128 SPP=1024 bash benchmarks/glass_mitsuba.sh OUT
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-glass_mitsuba}" size="${SIZE:-128}" spp="${SPP:-1024}"
py=benchmarks/.venv/bin/python
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$out"
python3 benchmarks/make_glass_panes.py "$out"
echo "| scene | glass | Mitsuba / rcsplat R | G | B | 8x8 block relMSE |" > "$out/table.md"
echo "|---|---|---|---|---|---|" >> "$out/table.md"
for s in none thin slab; do
  build/rcsplat reference "$out/$s.gltf" --width "$size" --height "$size" --sky 1,1,1 --bounces 3 --spp "$spp" \
    -o "$out/$s.ref.exr" > "$out/$s.ref.log"
  "$py" benchmarks/mitsuba_peer.py "$out/$s.gltf" --reference "$out/$s.ref.exr" --converged-spp "$spp" --spp "" \
    --glass-depth 4 -o "$out/mitsuba_$s" --json "$out/$s.mitsuba.json" | tee "$out/$s.mitsuba.log"
  "$py" - "$s" "$out/$s.mitsuba.json" >> "$out/table.md" <<'PY'
import json, sys
name, path = sys.argv[1:]
r = json.load(open(path))["agreement"]
glass = {"none": "none (control)", "thin": "thin-walled, tint (0.9, 0.8, 0.6): glTF one interface / Mitsuba thindielectric",
         "slab": "volume 0.3 thick, clear: Mitsuba dielectric"}[name]
m = r["mean_ratio_rgb"]
print(f"| {name} | {glass} | {m[0]:.4f} | {m[1]:.4f} | {m[2]:.4f} | {r['block_rel_mse']:.3e} |")
PY
done
cat "$out/table.md"
