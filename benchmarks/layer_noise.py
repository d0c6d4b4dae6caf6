#!/usr/bin/env python3
"""A sampled layer's own noise (issue 59 item 3): each image's LAYER (glossy or direct) against a converged one of
the same method (`rcsplat render ... --glossy-uniform --glossy-samples 256`, or `--light-uniform --light-samples
1024`), as compare's relMSE and 8x8 block relMSE of the difference over the converged frame's colour
((g - c)^2 / (colour^2 + 0.01)), with the frame's seconds from each image's --json summary (IMAGE with .json in place
of .exr).

  benchmarks/.venv/bin/python benchmarks/layer_noise.py LAYER CONVERGED.exr IMAGE.exr...
"""
import json
import sys

import numpy as np

from rcsplat_images import read_layer


def blocks(a):
    h, w = a.shape[0] // 8 * 8, a.shape[1] // 8 * 8
    return a[:h, :w].reshape(h // 8, 8, w // 8, 8, 3).mean((1, 3))


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    layer = sys.argv[1]
    converged, colour = read_layer(sys.argv[2], layer), read_layer(sys.argv[2])
    for path in sys.argv[3:]:
        image = read_layer(path, layer)
        seconds = json.load(open(path[: -len(".exr")] + ".json"))["seconds"]
        stage = seconds["glossy" if layer == "glossy" else "direct"]
        rel = ((image - converged) ** 2 / (colour ** 2 + 0.01)).mean()
        block = ((blocks(image) - blocks(converged)) ** 2 / (blocks(colour) ** 2 + 0.01)).mean()
        print(f"{path}: {layer} {stage:.2f} s of {seconds['total'] - seconds['kernel_build']:.2f} s; relMSE {rel:.3e}, "
              f"8x8 block {block:.3e}, mean / converged {image.mean() / converged.mean():.4f}")


if __name__ == "__main__":
    main()
