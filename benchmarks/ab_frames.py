#!/usr/bin/env python3
"""Two rcsplat binaries on the same frame, interleaved (A, B, A, B, ...), so that both see the same machine state:
medians of each pass's time and of the frame, and the ratio B / A measured in the same run.

    benchmarks/ab_frames.py OLD_BINARY NEW_BINARY SCENE --repeats 5 -- --width 1024 --height 768

Everything after `--` goes to both `rcsplat render` commands. One untimed warm-up run of each fills the kernel caches
(separate cache folders per binary, so neither loads the other's programs). --compare REF also reports each run's
indirect relMSE and block relMSE against REF (`rcsplat compare`, the reference's own noise removed)."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def render(binary, scene, extra, out_dir, tag, cache_dir):
    exr = os.path.join(out_dir, tag + ".exr")
    summary = os.path.join(out_dir, tag + ".json")
    env = dict(os.environ, RCSPLAT_CACHE_DIR=cache_dir)
    subprocess.run([binary, "render", scene, "-o", exr, "--json", summary] + extra, check=True, env=env,
                   stdout=subprocess.DEVNULL)
    with open(summary) as f:
        return exr, json.load(f)


def errors(binary, exr, reference, out_dir):
    report = os.path.join(out_dir, "compare.json")
    subprocess.run([binary, "compare", exr, reference, "--json", report], check=True, stdout=subprocess.DEVNULL)
    with open(report) as f:
        indirect = json.load(f)["indirect"]
    return (indirect.get("rel_mse_less_reference_noise", indirect["rel_mse"]),
            indirect.get("block_rel_mse_less_reference_noise", indirect["block_rel_mse"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("scene")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--compare", metavar="REF", help="a reference EXR to measure each run's error against")
    parser.add_argument("--json", help="write the medians here")
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    args = parser.parse_args(argv[:split])
    extra = argv[split + 1:]
    work = tempfile.mkdtemp(prefix="ab_frames_")
    binaries = {"A": os.path.abspath(args.old), "B": os.path.abspath(args.new)}
    caches = {k: os.path.join(work, "kernels_" + k) for k in binaries}
    for k, b in binaries.items():  # warm-up: kernel builds, file caches
        render(b, args.scene, extra, work, "warm_" + k, caches[k])
    runs = {k: [] for k in binaries}
    for r in range(args.repeats):
        for k, b in binaries.items():
            exr, summary = render(b, args.scene, extra, work, f"{k}{r}", caches[k])
            row = dict(summary["seconds"])
            row["records_placed"] = summary["cache"]["records"] if "cache" in summary else 0
            row["rays"] = summary["rays"]["records"]
            if args.compare:
                row["indirect_rel_mse"], row["indirect_block_rel_mse"] = errors(b, exr, args.compare, work)
            runs[k].append(row)
            print(f"run {r + 1}/{args.repeats} {k}: total {row['total']:.3f} s, records {row['records']:.3f} s",
                  file=sys.stderr)
    keys = [k for k in runs["A"][0] if isinstance(runs["A"][0][k], (int, float))]
    medians = {k: {key: statistics.median(row[key] for row in runs[k]) for key in keys} for k in runs}
    print(f"{'':28s}{'A (old)':>14s}{'B (new)':>14s}{'B / A':>9s}")
    for key in keys:
        a, b = medians["A"][key], medians["B"][key]
        if a == 0 and b == 0:
            continue
        ratio = f"{b / a:.3f}" if a else "-"
        print(f"{key:28s}{a:14.6g}{b:14.6g}{ratio:>9s}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"old": binaries["A"], "new": binaries["B"], "scene": args.scene, "render_args": extra,
                       "repeats": args.repeats, "medians": medians, "runs": runs}, f, indent=1)


if __name__ == "__main__":
    main()
