#!/usr/bin/env python3
"""Fireflies (issue 59 item 1): the share of an image's per-pixel relMSE held by pixels brighter than ten times the
reference's luminance plus one, and by the brightest 0.1% of pixels' errors, for the image and its indirect layer.
The relMSE is `rcsplat compare`'s: (x - r)^2 / (r^2 + 0.01), averaged over pixels and channels.

  benchmarks/.venv/bin/python benchmarks/firefly_share.py IMAGE.exr REFERENCE.exr [--json OUT.json]
"""
import argparse
import json

import numpy as np

from rcsplat_images import read_layer

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def shares(image, reference):
    per_pixel = ((image - reference) ** 2 / (reference ** 2 + 0.01)).mean(axis=-1)
    total = per_pixel.sum()
    bright = (image @ LUMINANCE) > 10.0 * (reference @ LUMINANCE) + 1.0
    top = np.sort(per_pixel.ravel())[::-1][: max(1, per_pixel.size // 1000)]
    return {"relmse": float(per_pixel.mean()), "bright_pixels": int(bright.sum()),
            "bright_share": float(per_pixel[bright].sum() / total) if total > 0 else 0.0,
            "top_0.1%_share": float(top.sum() / total) if total > 0 else 0.0,
            "mean_ratio": float((image @ LUMINANCE).mean() / (reference @ LUMINANCE).mean())}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("image")
    p.add_argument("reference")
    p.add_argument("--json")
    a = p.parse_args()
    report = {"image": shares(read_layer(a.image), read_layer(a.reference)),
              "indirect": shares(read_layer(a.image, "indirect"), read_layer(a.reference, "indirect"))}
    for layer, r in report.items():
        print(f"{layer:9s} relMSE {r['relmse']:.4g}  pixels > 10 ref + 1: {r['bright_pixels']} holding "
              f"{100 * r['bright_share']:.1f}%  top 0.1%: {100 * r['top_0.1%_share']:.1f}%  mean/ref {r['mean_ratio']:.4f}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=2)


if __name__ == "__main__":
    main()
