#!/usr/bin/env python3
"""Equal-error time: how long each peer needs to reach the error a cache render reaches, per metric.

Reads an `rcsplat sweep` CSV (and, optionally, the JSON of benchmarks/mitsuba_peer.py) and prints one Markdown table
per cache configuration: the cache's error and seconds, then for stratified path tracing and for path tracing plus
OIDN the seconds at which their error equals the cache's, log-log interpolated between the sample counts that bracket
it, and the ratio to the cache's time. A time marked ">" or "<" lies outside the sample counts run (extrapolated from
the last two or bounded by the fewest). Errors are the reference-noise-corrected columns where the sweep has them.

  python3 benchmarks/sweep_equal_error.py DIR/sweep.csv [--config cache_a0.3_16x32] [--mitsuba peer.json]
"""
import argparse
import csv
import json
import math

METRICS = [("indirect_rel_mse_less_noise", "indirect_rel_mse", "indirect relMSE"),
           ("indirect_block_rel_mse_less_noise", "indirect_block_rel_mse", "indirect block relMSE"),
           ("indirect_flip", None, "indirect FLIP"),
           ("full_rel_mse_less_noise", "full_rel_mse", "full relMSE"),
           ("full_block_rel_mse_less_noise", "full_block_rel_mse", "full block relMSE"),
           ("full_flip", None, "full FLIP")]


def seconds_at_error(runs, target):
    """runs: (seconds, error) of one method at increasing sample counts. Returns (seconds, flag): flag is "" inside
    the runs, ">" extrapolated past the most samples, "<" when the fewest samples already reach the target."""
    runs = sorted(runs)
    logs = [(math.log(s), math.log(e)) for s, e in runs if s > 0 and e > 0]
    if not logs:
        return None, ""
    if logs[0][1] <= math.log(target):
        return math.exp(logs[0][0]), "<"
    for (s0, e0), (s1, e1) in zip(logs, logs[1:]):
        if e0 >= math.log(target) >= e1 and e0 != e1:
            return math.exp(s0 + (math.log(target) - e0) / (e1 - e0) * (s1 - s0)), ""
    if len(logs) >= 2 and logs[-2][1] != logs[-1][1]:
        (s0, e0), (s1, e1) = logs[-2], logs[-1]
        if e1 < e0:  # still falling: extend the last segment
            return math.exp(s0 + (math.log(target) - e0) / (e1 - e0) * (s1 - s0)), ">"
    return None, ">"


def number(row, key, fallback=None):
    for k in (key, fallback):
        if k and row.get(k) not in (None, ""):
            return float(row[k])
    return None


def describe(seconds, flag, anchor):
    if seconds is None:
        return "not reached"
    return f"{flag}{seconds:.2f} s ({seconds / anchor:.1f}x)"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--config", action="append", help="cache configuration(s) to report (default: every one)")
    ap.add_argument("--mitsuba", help="JSON from benchmarks/mitsuba_peer.py run with --cache on the same render")
    a = ap.parse_args()
    with open(a.csv) as f:
        rows = list(csv.DictReader(f))
    caches = [r for r in rows if r["method"] == "cache" and (not a.config or r["config"] in a.config)]
    peers = {"path": [r for r in rows if r["method"] == "path"],
             "path+OIDN": [r for r in rows if r["method"] == "path+denoise"]}
    mitsuba = json.load(open(a.mitsuba)) if a.mitsuba else None
    for cache in caches:
        seconds = float(cache["seconds"])
        print(f"\n{cache['config']}: {seconds:.2f} s, {int(cache['records'])} records, "
              f"{float(cache['record_rays']) / 1e6:.1f} M record rays")
        print("| metric | cache | " + " | ".join(f"{p} at equal error" for p in peers) + " |")
        print("|---|---|" + "---|" * len(peers))
        for key, fallback, label in METRICS:
            target = number(cache, key, fallback)
            if target is None or target <= 0:
                continue
            cells = []
            for runs in peers.values():
                points = [(float(r["seconds"]), number(r, key, fallback)) for r in runs]
                cells.append(describe(*seconds_at_error([p for p in points if p[1]], target), seconds))
            print(f"| {label} | {target:.3g} | " + " | ".join(cells) + " |")
    if mitsuba and "cache" in mitsuba:
        c = mitsuba["cache"]
        anchor = c.get("seconds") or float("nan")
        for key in ("rel_mse", "block_rel_mse"):
            s = c.get(f"mitsuba_seconds_at_equal_{key}")
            flag = c.get(f"mitsuba_{key}_bound", "")
            print(f"Mitsuba 3 at the full image's equal {key}: {c[key]:.3g} -> {describe(s, flag, anchor)}")


if __name__ == "__main__":
    main()
