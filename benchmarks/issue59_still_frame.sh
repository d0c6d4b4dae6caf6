#!/usr/bin/env bash
# Issue 59: a still frame against path tracing + Open Image Denoise at equal time, one scene at one size. Renders the
# cache at the render defaults with --denoise (one EXR holds the denoised frame and, as noisy*, the frame as rendered),
# path tracing (--stratified) at each SPPS count with --denoise (OIDN inside rcsplat, its time in the frame's), and
# compares each against REF (a converged reference: `rcsplat reference SCENE --width W --height H --spp N`), full
# image and indirect layer, with benchmarks/firefly_share.py for the fireflies. A "+ OIDN" row's time holds OIDN's on
# the layers its image needs (path tracing: the colour; its indirect layer, denoised for compare, is not counted). Writes OUT/*.exr, OUT/*.json and
# OUT/table.md.
#   SPPS="8 16 32" bash benchmarks/issue59_still_frame.sh SCENE REF.exr OUT [W H]
# EXTRA="--environment sky.hdr" adds those arguments to every render (the reference must have been made with them).
set -euo pipefail
cd "$(dirname "$0")/.."
scene="$1" ref="$2" out="$3" width="${4:-512}" height="${5:-384}"
spps="${SPPS:-8 16 32}"
py=benchmarks/.venv/bin/python
mkdir -p "$out"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
size=(--width "$width" --height "$height")
read -r -a extra <<<"${EXTRA:-}"
size+=("${extra[@]}")
row() {  # name, exr, summary json, layer prefix ("" or noisy)
  local name="$1" exr="$2" summary="$3" prefix="$4"
  local img="$exr"
  if [ -n "$prefix" ]; then  # the frame as rendered: its noisy layers as an image of their own
    img="$out/$name.noisy.exr"
    "$py" - "$exr" "$img" <<'PY'
import sys
sys.path.insert(0, "benchmarks")
from rcsplat_images import read_layer, write_exr, attributes
src, dst = sys.argv[1], sys.argv[2]
layers = {k: read_layer(src, k) for k in ("albedo", "normal", "direct")}
layers["indirect"] = read_layer(src, "noisy_indirect")
write_exr(dst, read_layer(src, "noisy"), layers, attributes(src))
PY
  fi
  build/rcsplat compare "$img" "$ref" --json "$out/$name.compare.json" > /dev/null
  "$py" benchmarks/firefly_share.py "$img" "$ref" --json "$out/$name.fireflies.json" > /dev/null
  "$py" - "$name" "$summary" "$out/$name.compare.json" "$out/$name.fireflies.json" "$prefix" >> "$out/table.md" <<'PY'
import json, sys
name, summary, compare, fireflies, prefix = sys.argv[1:]
s, c, f = (json.load(open(p)) for p in (summary, compare, fireflies))
# The frame less kernel builds; as rendered: less all of OIDN; denoised: less the indirect layer's OIDN run, which
# only compare's indirect row needs (path tracing), not the image.
t = s["seconds"]
sec = t["total"] - t["kernel_build"] - (t["denoise"] if prefix else t["denoise_indirect_only"])
full, ind = c["full"], c.get("indirect", {})
print(f"| {name} | {sec:.2f} | {full['rel_mse']:.4g} | {full['block_rel_mse']:.4g} | {full['mean_flip']:.4f} | "
      f"{full['mean_ratio']:.4f} | {ind.get('block_rel_mse', float('nan')):.4g} | "
      f"{100 * f['image']['bright_share']:.1f}% ({f['image']['bright_pixels']}) |")
PY
}
echo "| way | s | relMSE | 8x8 block relMSE | FLIP | mean/ref | indirect 8x8 | > 10 ref + 1 (pixels) |" > "$out/table.md"
echo "|---|---|---|---|---|---|---|---|" >> "$out/table.md"
build/rcsplat render "$scene" "${size[@]}" --denoise -o "$out/cache.exr" --json "$out/cache.json" > "$out/cache.log"
row "cache" "$out/cache.exr" "$out/cache.json" noisy
row "cache + OIDN" "$out/cache.exr" "$out/cache.json" ""
for spp in $spps; do
  build/rcsplat render "$scene" "${size[@]}" --gi path --spp "$spp" --stratified --denoise -o "$out/pt$spp.exr" \
    --json "$out/pt$spp.json" > "$out/pt$spp.log"
  row "PT $spp spp" "$out/pt$spp.exr" "$out/pt$spp.json" noisy
  row "PT $spp spp + OIDN" "$out/pt$spp.exr" "$out/pt$spp.json" ""
done
cat "$out/table.md"
