#!/usr/bin/env python3
"""benchmarks/moving/moving_walk.sh's table: time a frame after the first (median and mean) of each sequence, error at
each judged frame (rcsplat compare's JSON: full relMSE, full 8x8, FLIP, indirect less the reference's noise), flicker
(rcsplat flicker's JSON, temporal relMSE of the indirect layer) and the ghost metric (ghosts.json).

    benchmarks/.venv/bin/python benchmarks/moving/summary.py OUT"""
import csv
import glob
import json
import os
import statistics
import sys


def frame_times(path, extra=None):
    rows = list(csv.DictReader(open(path)))[1:]
    seconds = [float(r["seconds"]) for r in rows]
    if extra:
        seconds = [s + extra.get(int(r["frame"]), 0.0) for s, r in zip(seconds, rows)]
    return statistics.median(seconds), statistics.mean(seconds)


def main():
    out = sys.argv[1]
    oidn = {}
    for p in glob.glob(os.path.join(out, "oidn", "*.json")):
        oidn[int(os.path.basename(p)[:4])] = json.load(open(p)).get("seconds", 0.0)
    times = {"kept": frame_times(os.path.join(out, "kept.csv")),
             "fresh": frame_times(os.path.join(out, "fresh.csv")),
             "oidn": frame_times(os.path.join(out, "path.csv"), oidn)}
    print("time a frame after the first, median / mean (s):")
    for m, (med, mean) in times.items():
        print("  %-6s %.3f / %.3f   (%.2fx / %.2fx the cache per frame's)" % (
            m, med, mean, med / times["fresh"][0], mean / times["fresh"][1]))
    print("error at the judged frames (full relMSE, full 8x8, FLIP, indirect relMSE less noise, indirect 8x8 less noise):")
    for p in sorted(glob.glob(os.path.join(out, "compare_*.json"))):
        d = json.load(open(p))
        name = os.path.basename(p)[len("compare_"):-len(".json")]
        ind = d.get("indirect", {})
        print("  %-12s %.4e %.4e %.4f %.4e %.4e" % (name, d["full"]["rel_mse"], d["full"]["block_rel_mse"],
                                                 d["full"]["mean_flip"], ind.get("rel_mse_less_reference_noise", float("nan")),
                                                 ind.get("block_rel_mse_less_reference_noise", float("nan"))))
    print("flicker (temporal relMSE of the indirect layer; path + OIDN: of the colour):")
    for m in ("kept", "fresh", "oidn"):
        p = os.path.join(out, "flicker_%s.json" % m)
        if os.path.exists(p):
            print("  %-6s %.4e" % (m, json.load(open(p))["temporal_rel_mse"]))
    ghosts = os.path.join(out, "ghosts.txt")
    if os.path.exists(ghosts):
        print("ghosts:\n" + "".join("  " + line for line in open(ghosts)))


if __name__ == "__main__":
    main()
