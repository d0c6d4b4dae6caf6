#!/usr/bin/env python3
"""Equal-error comparison: radiance cache splatting against path tracing on the same device.

For each cache accuracy, renders with `rcsplat render --gi splat`, measures the indirect layer's relMSE against a
converged reference (`rcsplat compare`), then finds the path-traced sample count reaching the same relMSE, plain and
with a stratified grid, by doubling the samples and interpolating on the 1/spp law between the two bracketing runs.
Times compared are those of the indirect light alone (cache: records + placement + splat + resolve; path: path pass):
G-buffer and direct light are shared by both and excluded. Standard library only.

  benchmarks/equal_error.py SCENE --width 1024 --height 768 --reference ref.exr --accuracy 0.3 0.15
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{result.stderr}")
    return result


_runs = {}


def render(args, extra, tmp, tag):
    """One render and its comparison with the reference; path runs are reused across accuracies."""
    if tag in _runs:
        return _runs[tag]
    _runs[tag] = _render(args, extra, tmp, tag)
    return _runs[tag]


def _render(args, extra, tmp, tag):
    exr, summary = os.path.join(tmp, tag + ".exr"), os.path.join(tmp, tag + ".json")
    cmd = [args.rcsplat, "render", "-q", "--width", str(args.width), "--height", str(args.height),
           "--light-samples", "1", "--bounces", "1", "--pixel-samples", "1", "-o", exr, "--json", summary] + ([args.scene] if args.scene else []) + extra
    if args.device:
        cmd += ["--device", args.device]
    run(cmd)
    compare = os.path.join(tmp, tag + ".cmp.json")
    run([args.rcsplat, "compare", exr, args.reference, "--json", compare])
    with open(summary) as f:
        s = json.load(f)
    with open(compare) as f:
        c = json.load(f)
    sec = s["seconds"]
    indirect_s = sec["records"] + sec["placement"] + sec["splat"] + sec["resolve"] + sec["path"]
    ind = c["indirect"]
    # Less the reference's own noise where the reference carries its variance.
    return {"rel_mse": ind.get("rel_mse_less_reference_noise", ind["rel_mse"]), "seconds": indirect_s, "summary": s}


def equal_error_time(args, target, stratified, tmp):
    """Seconds the path tracer needs to reach relMSE target: doubling spp, then interpolating relMSE ~ c / spp^k
    between the bracketing runs (extrapolating past --max-spp)."""
    spp, previous, rows = args.start_spp, None, []
    while True:
        flags = ["--gi", "path", "--spp", str(spp)] + (["--stratified"] if stratified else [])
        r = render(args, flags, tmp, f"path{spp}{'s' if stratified else ''}")
        rows.append((spp, r["rel_mse"], r["seconds"]))
        if r["rel_mse"] <= target or spp >= args.max_spp:
            break
        previous = (spp, r)
        spp *= 2
    if r["rel_mse"] > target and previous is None:
        return None, rows
    # Past --max-spp the same law extrapolates from the last two runs (plain sampling follows 1/spp closely); the
    # runs are in the JSON so that an extrapolation shows.
    if previous is None:  # one sample per pixel already suffices: its time is an upper bound
        return r["seconds"], rows
    # Between the bracketing runs relMSE = c / spp^k; solve for the spp giving the target, time linear in spp.
    (s0, r0), (s1, r1) = previous, (spp, r)
    k = math.log(r0["rel_mse"] / r1["rel_mse"]) / math.log(s1 / s0)
    spp_star = s0 * (r0["rel_mse"] / target) ** (1.0 / k)
    per_sample = (r1["seconds"] - r0["seconds"]) / (s1 - s0)
    return r0["seconds"] + per_sample * (spp_star - s0), rows


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", nargs="?", default="", help="glTF scene (default: the built-in Cornell box)")
    p.add_argument("--reference", required=True, help="converged reference EXR (rcsplat reference)")
    p.add_argument("--width", type=int, default=1024)
    p.add_argument("--height", type=int, default=768)
    p.add_argument("--accuracy", type=float, nargs="+", default=[0.3])
    p.add_argument("--hemisphere", default="16x32")
    p.add_argument("--spacing", default="3,20")
    p.add_argument("--start-spp", type=int, default=1, help="first path sample count (then doubled)")
    p.add_argument("--max-spp", type=int, default=4096)
    p.add_argument("--rcsplat", default=os.path.join(os.path.dirname(__file__), "..", "build", "rcsplat"))
    p.add_argument("--device", help="OpenCL device (index or name substring); default: rcsplat's choice")
    p.add_argument("--json", help="also write the table as JSON")
    args = p.parse_args()
    table = []
    with tempfile.TemporaryDirectory() as tmp:
        for a in args.accuracy:
            flags = ["--gi", "splat", "--accuracy", str(a), "--hemisphere", args.hemisphere, "--spacing", args.spacing]
            cache = render(args, flags, tmp, f"splat{a}")
            row = {"accuracy": a, "records": cache["summary"]["cache"]["records"], "rel_mse": cache["rel_mse"],
                   "seconds": cache["seconds"]}
            for stratified in (False, True):
                t, rows = equal_error_time(args, cache["rel_mse"], stratified, tmp)
                key = "stratified" if stratified else "plain"
                row[key] = {"seconds": t, "ratio": (t / cache["seconds"]) if t else None,
                            "runs": [{"spp": s, "rel_mse": e, "seconds": sec} for s, e, sec in rows]}
            table.append(row)
            print(f"a={a}: {row['records']} records, relMSE {row['rel_mse']:.3e} in {row['seconds']:.2f} s; "
                  f"path plain {row['plain']['seconds']} s (x{row['plain']['ratio']}), "
                  f"stratified {row['stratified']['seconds']} s (x{row['stratified']['ratio']})", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(table, f, indent=2)


if __name__ == "__main__":
    main()
