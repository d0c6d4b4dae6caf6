#!/usr/bin/env python3
"""The ghost metric of issue 62 item 4: error restricted to the pixels whose indirect light the motion changed.

For each judged frame f (one with a reference in OUT/ref), the changed pixels are those whose indirect light in the
cache placed anew at frame f (OUT/fresh) differs from that cache's frame 0 by more than 10% of the larger: where
the moving object is, was, shadows or lights. Over them, each sequence's relMSE of the indirect layer against the
reference (relative to ref^2 + 0.01, as rcsplat compare), less the reference's own expected noise there (its
indirect_variance layer); path tracing + OIDN has no separate indirect layer, so its colour is judged against the
reference's colour. A ghost is light left where the object was: the kept records' number above the fresh cache's.

    benchmarks/.venv/bin/python benchmarks/moving/ghosts.py OUT FRAME..."""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from rcsplat_images import read_layer  # noqa: E402

OFFSET = 0.01


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)


def rel_mse(image, ref, mask):
    return float(np.mean(((image - ref) ** 2 / (ref * ref + OFFSET))[mask]))


def main():
    out, frames = sys.argv[1], [int(f) for f in sys.argv[2:]]
    first = read_layer(os.path.join(out, "fresh", "0000.exr"), "indirect")
    result = []
    for f in frames:
        n = "%04d" % f
        ref_path = os.path.join(out, "ref", n + ".exr")
        if not os.path.exists(ref_path):
            continue
        ref, variance = read_layer(ref_path, "indirect"), read_layer(ref_path, "indirect_variance")
        fresh = read_layer(os.path.join(out, "fresh", n + ".exr"), "indirect")
        a, b = luminance(first), luminance(fresh)
        changed = np.abs(a - b) > 0.1 * np.maximum(np.maximum(a, b), 1e-4)
        mask = np.repeat(changed[..., None], 3, axis=-1)
        noise = float(np.mean((variance / (ref * ref + OFFSET))[mask]))
        row = {"frame": f, "changed_pixels": int(changed.sum()), "reference_noise": noise}
        for m in ("kept", "fresh"):
            image = read_layer(os.path.join(out, m, n + ".exr"), "indirect")
            row[m] = rel_mse(image, ref, mask) - noise
        oidn = read_layer(os.path.join(out, "oidn", n + ".exr"))
        row["oidn_full"] = rel_mse(oidn, read_layer(ref_path), mask) - noise
        row["kept_over_fresh"] = row["kept"] / row["fresh"] if row["fresh"] > 0 else float("nan")
        result.append(row)
        print("frame %d: %d changed pixels; relMSE there less the reference's noise (%.3g): kept %.4g, fresh %.4g "
              "(kept/fresh %.3f), path + OIDN (colour) %.4g" % (f, row["changed_pixels"], noise, row["kept"],
                                                                row["fresh"], row["kept_over_fresh"], row["oidn_full"]))
    with open(os.path.join(out, "ghosts.json"), "w") as fh:
        json.dump(result, fh, indent=1)


if __name__ == "__main__":
    main()
