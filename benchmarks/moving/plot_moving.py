#!/usr/bin/env python3
"""Time a frame of each sequence of benchmarks/moving/moving_walk.sh, one panel a scene.

    benchmarks/.venv/bin/python benchmarks/moving/plot_moving.py OUT.png NAME=DIR [NAME=DIR ...]"""
import csv
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def seconds(path):
    rows = list(csv.DictReader(open(path)))
    return [int(r["frame"]) for r in rows], [float(r["seconds"]) for r in rows]


def main():
    out, runs = sys.argv[1], [a.split("=", 1) for a in sys.argv[2:]]
    fig, axes = plt.subplots(1, len(runs), figsize=(6 * len(runs), 4), squeeze=False)
    for ax, (name, d) in zip(axes[0], runs):
        oidn = {int(os.path.basename(p)[:4]): json.load(open(p))["seconds"] for p in glob.glob(os.path.join(d, "oidn", "*.json"))}
        for label, csv_name in (("records kept", "kept.csv"), ("cache per frame", "fresh.csv")):
            f, s = seconds(os.path.join(d, csv_name))
            ax.plot(f[1:], s[1:], label=label)
        f, s = seconds(os.path.join(d, "path.csv"))
        ax.plot(f[1:], [x + oidn.get(i, 0.0) for i, x in zip(f[1:], s[1:])], label="path 4 spp + OIDN")
        ax.set_title(name)
        ax.set_xlabel("frame")
        ax.set_ylabel("seconds")
        ax.set_ylim(bottom=0)
        ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
