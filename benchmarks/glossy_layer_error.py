#!/usr/bin/env python3
"""The glossy pass's own noise (issue 59 item 3): each image's glossy layer against a converged one of the same
method (`rcsplat render ... --glossy-uniform --glossy-samples 256`), as compare's relMSE and 8x8 block relMSE of the
difference over the converged frame's colour ((g - c)^2 / (colour^2 + 0.01)), with the glossy pass's seconds and rays
from each image's --json summary (IMAGE with .json in place of .exr).

  benchmarks/.venv/bin/python benchmarks/glossy_layer_error.py CONVERGED.exr IMAGE.exr...
"""
import json
import sys

import numpy as np

from rcsplat_images import read_layer


def blocks(a):
    h, w = a.shape[0] // 8 * 8, a.shape[1] // 8 * 8
    return a[:h, :w].reshape(h // 8, 8, w // 8, 8, 3).mean((1, 3))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    converged, colour = read_layer(sys.argv[1], "glossy"), read_layer(sys.argv[1])
    for path in sys.argv[2:]:
        glossy = read_layer(path, "glossy")
        summary = json.load(open(path[: -len(".exr")] + ".json"))["specular"]
        rel = ((glossy - converged) ** 2 / (colour ** 2 + 0.01)).mean()
        block = ((blocks(glossy) - blocks(converged)) ** 2 / (blocks(colour) ** 2 + 0.01)).mean()
        print(f"{path}: glossy {summary['seconds']:.2f} s, {summary['glossy_rays']} rays; relMSE {rel:.3e}, "
              f"8x8 block {block:.3e}, mean / converged {glossy.mean() / converged.mean():.4f}")


if __name__ == "__main__":
    main()
