#!/usr/bin/env bash
# Issue 61 item 6: rcsplat's own glTF interior (benchmarks/make_glass_interior.py: glass windows, a glass vase with a
# volume, normal-mapped brick walls, a clearcoated ball and a sheen cushion) lit by a sky with a sun through the
# windows (benchmarks/make_sky.py), as a still frame against path tracing + OIDN at equal time
# (benchmarks/issue59_still_frame.sh) and images of the cache and the reference at several exposures. Writes OUT/.
#   REF_SPP=4096 SPPS="4 8 16" bash benchmarks/glass_interior.sh OUT [W H]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-glass_interior}" width="${2:-320}" height="${3:-240}"
ref_spp="${REF_SPP:-4096}"
py=benchmarks/.venv/bin/python
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$out"
python3 benchmarks/make_glass_interior.py "$out/scene" > /dev/null
python3 benchmarks/make_sky.py "$out/scene/sky.hdr" --sun-elevation 35 --sun-azimuth 10
scene="$out/scene/glass_interior.gltf"
extra="--environment $out/scene/sky.hdr"
[ -f "$out/reference.exr" ] ||
  build/rcsplat reference "$scene" --width "$width" --height "$height" $extra --spp "$ref_spp" \
    -o "$out/reference.exr" --json "$out/reference.json" > "$out/reference.log"
EXTRA="$extra" bash benchmarks/issue59_still_frame.sh "$scene" "$out/reference.exr" "$out/still" "$width" "$height"
# Images at several exposures (stops), tone-mapped as rcsplat's PNGs are: the cache as rendered and denoised, the
# best path-traced + OIDN row, and the reference.
"$py" - "$out" <<'PY'
import glob, os, sys
sys.path.insert(0, "benchmarks")
from rcsplat_images import exposure_grid
out = sys.argv[1]
rows = [("cache", f"{out}/still/cache.noisy.exr"), ("cache + OIDN", f"{out}/still/cache.exr")]
pts = sorted(glob.glob(f"{out}/still/pt*.exr"), key=lambda p: int(os.path.basename(p)[2:].split(".")[0]))
pts = [p for p in pts if ".noisy" not in p]
if pts:
    rows.append((os.path.basename(pts[-1]).split(".")[0].replace("pt", "PT ") + " spp + OIDN", pts[-1]))
rows.append(("reference", f"{out}/reference.exr"))
exposure_grid(rows, (-4, 0, 2), f"{out}/exposures.png", dpi=110)
print(f"{out}/exposures.png")
PY
