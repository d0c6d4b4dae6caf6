#!/usr/bin/env python3
"""Path tracing plus Intel Open Image Denoise: the competitor a user would pick today (issue 12). Denoises an rcsplat
render's image and its indirect layer with OIDN's RT filter (PyPI pyoidn, high quality, HDR), fed rcsplat's own
albedo and normal layers as clean auxiliary images, and writes an EXR with both layers (and the auxiliaries) that
`rcsplat compare` judges like any render. `rcsplat sweep` calls it for its denoised points.

The time reported is the denoiser's on the image alone, after a warm-up call (the one-off device setup is not a
per-frame cost); denoising the indirect layer as well is for measuring only and not counted.

  benchmarks/setup_python.sh                     # once: the benchmark environment (benchmarks/.venv)
  benchmarks/.venv/bin/python benchmarks/denoise.py noisy.exr denoised.exr [--json time.json]
"""
import argparse
import json
import time

import numpy as np
import pyoidn

from rcsplat_images import attributes, read_layer, write_exr


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--json", help="write {seconds, ...} here")
    p.add_argument("--quality", default="high", choices=["high", "balanced", "fast"])
    a = p.parse_args()
    color = read_layer(a.input)
    albedo = np.clip(read_layer(a.input, "albedo"), 0.0, 1.0)
    normal = np.clip(read_layer(a.input, "normal"), -1.0, 1.0)

    def run(image, rows=slice(None), cols=slice(None)):
        return pyoidn.denoise(np.ascontiguousarray(image[rows, cols]), np.ascontiguousarray(albedo[rows, cols]),
                              np.ascontiguousarray(normal[rows, cols]), hdr=True, clean_aux=True, quality=a.quality)

    run(color, slice(0, 16), slice(0, 16))  # warm-up: the device and filter are made once per process
    start = time.perf_counter()
    denoised = run(color)
    seconds = time.perf_counter() - start
    layers = {"albedo": albedo}
    try:
        layers["indirect"] = run(read_layer(a.input, "indirect"))
    except SystemExit:
        pass  # a render without indirect light
    header = {k: v for k, v in attributes(a.input).items()}
    header["rcsplat:denoised"] = f"OIDN {a.quality} (pyoidn {getattr(pyoidn, '__version__', '?')})"
    write_exr(a.output, denoised, layers, header)
    report = {"seconds": seconds, "input": a.input, "output": a.output, "quality": a.quality,
              "width": int(color.shape[1]), "height": int(color.shape[0])}
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=2)
    print(f"denoised {a.input} -> {a.output} in {seconds:.3f} s (OIDN {a.quality})")


if __name__ == "__main__":
    main()
