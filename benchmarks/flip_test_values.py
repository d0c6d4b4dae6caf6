#!/usr/bin/env python3
"""Prints the values tests/flip_test.cpp checks rcsplat's FLIP against, computed by NVIDIA's flip-evaluator (PyPI) on
the test's formula images. Rerun when the formulas change: benchmarks/flip_test_values.py (benchmark environment)."""
import math

import flip_evaluator
import numpy as np

W, H = 48, 32


def images():
    ref = np.zeros((H, W, 3), np.float32)
    test = np.zeros((H, W, 3), np.float32)
    for y in range(H):
        for x in range(W):
            for c in range(3):
                r = 0.5 + 0.4 * math.sin(0.3 * x + 0.2 * y + c)
                t = r + (0.1 * math.sin(1.7 * x * y + c) if 10 <= x < 30 else 0.0)
                if 5 <= x < 10 and 5 <= y < 10:
                    t = 0.0
                ref[y, x, c], test[y, x, c] = r, min(max(t, 0.0), 1.0)
    return ref, test


ref, test = images()
error_map, mean, _ = flip_evaluator.evaluate(ref, test, "LDR", inputsRGB=True, applyMagma=False)
error_map = np.asarray(error_map).reshape(H, W)
print(f"mean {mean:.7f}")
for x, y in [(0, 0), (7, 7), (12, 20), (20, 3), (40, 25), (47, 31)]:
    print(f"pixel ({x}, {y}) {error_map[y, x]:.7f}")
