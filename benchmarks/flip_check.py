#!/usr/bin/env python3
"""Checks rcsplat's own LDR-FLIP (host/image/flip.cpp) against NVIDIA's flip-evaluator package (PyPI) on EXR pairs:
both tone-mapped as rcsplat's PNGs are, then FLIP by each. Prints both means and the per-pixel differences; exits 1
when the means differ by more than --tolerance. Needs the benchmark environment (benchmarks/setup_python.sh).

  benchmarks/flip_check.py build/rcsplat image.exr reference.exr [--layer indirect] [--exposure 0]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import flip_evaluator
import numpy as np

from rcsplat_images import display, read_layer


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("rcsplat")
    p.add_argument("image")
    p.add_argument("reference")
    p.add_argument("--layer", default="", help="'' (the image) or indirect")
    p.add_argument("--exposure", type=float, default=0.0)
    p.add_argument("--tolerance", type=float, default=1e-3, help="largest accepted difference of the means")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "c.json")
        subprocess.run([a.rcsplat, "compare", a.image, a.reference, "--exposure", str(a.exposure), "--json", out],
                       check=True, capture_output=True)
        with open(out) as f:
            ours = json.load(f)[a.layer or "full"]["mean_flip"]
    ref = display(read_layer(a.reference, a.layer), a.exposure)
    test = display(read_layer(a.image, a.layer), a.exposure)
    error_map, theirs, _ = flip_evaluator.evaluate(ref, test, "LDR", inputsRGB=True, applyMagma=False)
    print(f"mean FLIP: rcsplat {ours:.6f}, flip-evaluator {theirs:.6f}, difference {ours - theirs:+.2e}")
    sys.exit(0 if abs(ours - theirs) <= a.tolerance else 1)


if __name__ == "__main__":
    main()
