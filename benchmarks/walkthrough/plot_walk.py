#!/usr/bin/env python3
"""Time per frame and flicker per pair of frames along a walkthrough (benchmarks/walkthrough/sponza_walk.sh): records
kept across frames, a cache per frame, and path tracing plus OIDN. Writes OUT/walk.png and prints the medians.

  benchmarks/.venv/bin/python benchmarks/walkthrough/plot_walk.py OUT
"""
import csv
import glob
import json
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def frame_seconds(path):
    with open(path) as f:
        return {int(r["frame"]): float(r["seconds"]) for r in csv.DictReader(f)}


def main():
    out = sys.argv[1]
    times = {"records kept": frame_seconds(os.path.join(out, "kept.csv")),
             "cache per frame": frame_seconds(os.path.join(out, "fresh.csv"))}
    path = frame_seconds(os.path.join(out, "path.csv"))
    denoise = {}
    for j in glob.glob(os.path.join(out, "oidn", "*.json")):
        denoise[int(os.path.basename(j).split(".")[0])] = json.load(open(j))["seconds"]
    times["path tracing + OIDN"] = {f: s + denoise.get(f, 0.0) for f, s in path.items()}
    flicker = {}
    for name, key in (("records kept", "kept"), ("cache per frame", "fresh"), ("path tracing + OIDN", "oidn"),
                      ("frozen cache (the floor)", "frozen")):
        p = os.path.join(out, f"flicker_{key}_demodulated.json")
        if os.path.exists(p):
            flicker[name] = {q["frame"]: q["rel_mse"] for q in json.load(open(p))["pairs"]}
    fig, (a, b) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for name, series in times.items():
        frames = sorted(series)
        a.plot(frames, [series[f] for f in frames], label=name)
        later = [series[f] for f in frames[1:]]
        print(f"{name}: median seconds a frame after the first {statistics.median(later):.3f}")
    a.set_yscale("log")
    a.set_ylabel("seconds a frame")
    a.legend()
    for name, series in flicker.items():
        frames = sorted(series)
        b.plot(frames, [series[f] for f in frames], label=name)
        print(f"{name}: median temporal relMSE {statistics.median(series.values()):.4g}")
    b.set_yscale("log")
    b.set_ylabel("temporal relMSE, indirect over albedo")
    b.set_xlabel("frame")
    b.legend()
    fig.suptitle(sys.argv[2] if len(sys.argv) > 2 else "Sponza walk, 512 x 384")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "walk.png"), dpi=110)


if __name__ == "__main__":
    main()
