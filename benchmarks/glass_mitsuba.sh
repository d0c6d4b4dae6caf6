#!/usr/bin/env bash
# Issue 61 item 4: rcsplat's glass against Mitsuba 3's (thindielectric, dielectric) on the small scenes of
# benchmarks/make_glass_panes.py under a uniform sky: each scene's converged rcsplat reference against Mitsuba's
# converged render (benchmarks/mitsuba_peer.py), mean ratio per channel over the floor seen through the glass and over
# the rest, each divided by the control's ratio over the same pixels (the floor alone), so that what the two renderers
# do differently without glass (their floor BRDFs) drops out. Writes OUT/table.md.
#   bash benchmarks/setup_python.sh   # once
#   SIZE=128 SPP=1024 bash benchmarks/glass_mitsuba.sh OUT
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-glass_mitsuba}" size="${SIZE:-128}" spp="${SPP:-1024}"
py=benchmarks/.venv/bin/python
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$out"
python3 benchmarks/make_glass_panes.py "$out"
for s in none thin clear slab; do
  build/rcsplat reference "$out/$s.gltf" --width "$size" --height "$size" --sky 1,1,1 --bounces 3 --spp "$spp" \
    -o "$out/$s.ref.exr" > "$out/$s.ref.log"
  "$py" benchmarks/mitsuba_peer.py "$out/$s.gltf" --reference "$out/$s.ref.exr" --converged-spp "$spp" --spp "" \
    --glass-depth 4 -o "$out/mitsuba_$s" --json "$out/$s.mitsuba.json" > "$out/$s.mitsuba.log"
done
# The floor seen through the glass's top: x in [-1.5, 1.5], z in [-2, 1] at y = 1.2, from the camera at (0, 5, 3.5).
"$py" - "$out" "$spp" > "$out/table.md" <<'PY'
import sys
sys.path.insert(0, "benchmarks")
import numpy as np
from rcsplat_images import read_layer
out, spp = sys.argv[1], sys.argv[2]
eye = np.array([0.0, 5.0, 3.5])
glass = {"none": "none (control)", "thin": "thin-walled, tint (0.9, 0.8, 0.6)", "clear": "thin-walled, untinted",
         "slab": "volume 0.3 thick, clear"}
ratios = {}
print("| scene | glass | region | pixels | Mitsuba / rcsplat R | G | B | over the control's R | G | B |")
print("|---|---|---|---|---|---|---|---|---|---|")
for s in ("none", "thin", "clear", "slab"):
    ref = read_layer(f"{out}/{s}.ref.exr")
    mit = read_layer(f"{out}/mitsuba_{s}/mitsuba_{spp}spp.exr")
    pos = read_layer(f"{out}/{s}.ref.exr", "position")
    d = pos - eye
    hit = eye + d * ((1.2 - eye[1]) / d[..., 1])[..., None]
    through = (np.abs(hit[..., 0]) < 1.5) & (hit[..., 2] > -2.0) & (hit[..., 2] < 1.0) & (pos[..., 1] < 0.01)
    for region, mask in (("through the glass", through), ("beside it", ~through)):
        r = mit[mask].mean(axis=0) / ref[mask].mean(axis=0)
        ratios[(s, region)] = r
        n = r / ratios[("none", region)]
        print(f"| {s} | {glass[s]} | {region} | {int(mask.sum())} | {r[0]:.4f} | {r[1]:.4f} | {r[2]:.4f} | "
              f"{n[0]:.4f} | {n[1]:.4f} | {n[2]:.4f} |")
PY
cat "$out/table.md"
