#!/usr/bin/env bash
# Issue 61 item 2: light through a curved glass volume, by the glass caustic map (--light-through-glass caustics) and
# by straight shadow rays (the default), against Mitsuba 3's particle tracer (ptracer, which follows a point light's
# photons through its dielectric) on benchmarks/make_glass_ball.py's ball over the floor. Mean ratio per channel,
# Mitsuba over rcsplat, over the floor within 1.2 of the point below the ball (the caustic, inside the ball's shadow)
# and beyond 2.5 of it (direct light alone, the control); the cache's frame with the map and its time beside the
# default's. Writes OUT/table.md and images at -2, 0 and +2 stops.
#   bash benchmarks/setup_python.sh   # once
#   SIZE=128 SPP=256 bash benchmarks/glass_caustics.sh OUT
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-glass_caustics}" size="${SIZE:-128}" spp="${SPP:-256}"
py=benchmarks/.venv/bin/python
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
mkdir -p "$out"
python3 benchmarks/make_glass_ball.py "$out"
scene="$out/ball.gltf"
for mode in caustics straight; do
  build/rcsplat reference "$scene" --width "$size" --height "$size" --bounces 2 --spp "$spp" \
    --light-through-glass "$mode" -o "$out/$mode.ref.exr" > "$out/$mode.ref.log"
  build/rcsplat render "$scene" --width "$size" --height "$size" --bounces 2 --light-through-glass "$mode" \
    -o "$out/$mode.cache.exr" --json "$out/$mode.cache.json" > "$out/$mode.cache.log"
done
"$py" benchmarks/mitsuba_peer.py "$scene" --reference "$out/caustics.ref.exr" --converged-spp "$spp" --spp "" \
  --glass-depth 6 --integrator ptracer --bsdf diffuse -o "$out/mitsuba" --json "$out/mitsuba.json" > "$out/mitsuba.log"
"$py" - "$out" "$spp" > "$out/table.md" <<'PY'
import json
import sys
sys.path.insert(0, "benchmarks")
import numpy as np
from rcsplat_images import exposure_grid, read_layer
out, spp = sys.argv[1], sys.argv[2]
mit = read_layer(f"{out}/mitsuba/mitsuba_{spp}spp.exr")
pos = read_layer(f"{out}/caustics.ref.exr", "position")
# Floor pixels the camera sees directly: a particle tracer cannot see the floor through the ball (a specular chain to
# the camera), so pixels whose view crosses the ball's sphere are left out.
eye, centre = np.array([0.0, 5.0, 3.5]), np.array([0.0, 2.5, -0.5])
view = pos - eye
t = np.clip(((centre - eye) * view).sum(axis=-1) / (view * view).sum(axis=-1), 0.0, 1.0)
misses_ball = np.linalg.norm(eye + view * t[..., None] - centre, axis=-1) > 1.0
on_floor = (np.abs(pos[..., 1]) < 1e-3) & misses_ball
d = np.hypot(pos[..., 0], pos[..., 2] + 0.5)
# The focus is a few pixels whose values are the map's light where their sample points fall (a point sample of a
# spot smaller than a pixel, where Mitsuba's particles integrate the pixel): it is reported apart from the ring.
regions = {"focus (within 0.15)": on_floor & (d < 0.15), "caustic ring (0.15 to 1.2)": on_floor & (d >= 0.15) & (d < 1.2),
           "lit floor (beyond 2.5)": on_floor & (d > 2.5)}
print("| rcsplat image | region | pixels | Mitsuba / rcsplat | over the lit floor's |")
print("|---|---|---|---|---|")
for image in ("caustics.ref", "caustics.cache", "straight.ref", "straight.cache"):
    img = read_layer(f"{out}/{image}.exr")
    ratio = {name: float(mit[mask].mean() / img[mask].mean()) for name, mask in regions.items()}
    for name, mask in regions.items():
        print(f"| {image} | {name} | {int(mask.sum())} | {ratio[name]:.4f} | "
              f"{ratio[name] / ratio['lit floor (beyond 2.5)']:.4f} |")
print()
for mode in ("caustics", "straight"):
    s = json.load(open(f"{out}/{mode}.cache.json"))
    print(f"- cache, {mode}: frame {s['seconds']['total']:.3f} s" +
          (f", glass caustic map {s['glass_caustics']['photons']} photons, {s['glass_caustics']['seconds']:.3f} s"
           if s.get("glass_caustics") else ""))
rows = [("cache, caustics", f"{out}/caustics.cache.exr"), ("cache, straight", f"{out}/straight.cache.exr"),
        ("Mitsuba ptracer", f"{out}/mitsuba/mitsuba_{spp}spp.exr")]
exposure_grid(rows, (-2, 0, 2), f"{out}/exposures.png")
PY
cat "$out/table.md"
