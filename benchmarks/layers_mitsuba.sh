#!/usr/bin/env bash
# Issue 61 item 4: rcsplat's clearcoat and sheen against Mitsuba 3's principled BSDF on the spheres of
# benchmarks/make_layer_spheres.py under a uniform sky: each scene's converged rcsplat reference against Mitsuba's
# converged render (benchmarks/mitsuba_peer.py --bsdf principled), the mean ratio per channel over the sphere, divided
# by the control's (the same sphere without layers, also principled in Mitsuba) so that the two base models' difference
# drops out. Mitsuba's clearcoat (GTR1, Fresnel at the half vector, weight 0.25 in Disney's model) and sheen (Disney's,
# a Schlick-weighted grazing term) are not glTF's (GGX with the view's Fresnel; Charlie): the ratios measure the models'
# difference as much as rcsplat. Writes OUT/table.md.
#   bash benchmarks/setup_python.sh   # once
#   SIZE=96 SPP=1024 bash benchmarks/layers_mitsuba.sh OUT
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-layers_mitsuba}" size="${SIZE:-96}" spp="${SPP:-1024}"
py=benchmarks/.venv/bin/python
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$out"
python3 benchmarks/make_layer_spheres.py "$out"
for s in base coat sheen; do
  build/rcsplat reference "$out/$s.gltf" --width "$size" --height "$size" --sky 1,1,1 --bounces 3 --spp "$spp" \
    -o "$out/$s.ref.exr" > "$out/$s.ref.log"
  "$py" benchmarks/mitsuba_peer.py "$out/$s.gltf" --reference "$out/$s.ref.exr" --converged-spp "$spp" --spp "" \
    --bsdf principled -o "$out/mitsuba_$s" --json "$out/$s.mitsuba.json" > "$out/$s.mitsuba.log"
done
"$py" - "$out" "$spp" > "$out/table.md" <<'PY'
import sys
sys.path.insert(0, "benchmarks")
import numpy as np
from rcsplat_images import read_layer
out, spp = sys.argv[1], sys.argv[2]
centre, radius = np.array([0.0, 1.0, -0.5]), 1.0
layer = {"base": "none (control)", "coat": "clearcoat 1, roughness 0.1", "sheen": "white sheen, roughness 0.5"}
ratios = {}
print("| scene | layer | sphere pixels | Mitsuba / rcsplat R | G | B | over the control's R | G | B |")
print("|---|---|---|---|---|---|---|---|---|")
for s in ("base", "coat", "sheen"):
    ref = read_layer(f"{out}/{s}.ref.exr")
    mit = read_layer(f"{out}/mitsuba_{s}/mitsuba_{spp}spp.exr")
    pos = read_layer(f"{out}/{s}.ref.exr", "position")
    mask = np.abs(np.linalg.norm(pos - centre, axis=-1) - radius) < 0.02
    r = mit[mask].mean(axis=0) / ref[mask].mean(axis=0)
    ratios[s] = r
    n = r / ratios["base"]
    print(f"| {s} | {layer[s]} | {int(mask.sum())} | {r[0]:.4f} | {r[1]:.4f} | {r[2]:.4f} | "
          f"{n[0]:.4f} | {n[1]:.4f} | {n[2]:.4f} |")
PY
cat "$out/table.md"
