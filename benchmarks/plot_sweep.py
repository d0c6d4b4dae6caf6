#!/usr/bin/env python3
"""Draws accuracy_vs_time.png from an `rcsplat sweep` CSV: error (log) against seconds (log), one panel per metric
(indirect layer: per-pixel relMSE, relMSE of block means, mean FLIP; full image: relMSE), every cache configuration
beside path tracing at each sample count and path tracing plus denoising, and the Pareto front of each panel (the
runs no other run beats in both time and error) ringed and joined. Runs by hand on any sweep.csv:

  python3 benchmarks/plot_sweep.py DIR/sweep.csv [-o DIR/accuracy_vs_time.png]
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

PANELS = [("indirect_rel_mse_less_noise", "indirect_rel_mse", "indirect relMSE (per pixel)"),
          ("indirect_block_rel_mse_less_noise", "indirect_block_rel_mse", "indirect relMSE of block means"),
          ("indirect_flip", None, "indirect mean FLIP"),
          ("full_rel_mse", None, "full image relMSE (per pixel)")]
STYLE = {"cache": dict(color="tab:blue", marker="o"), "path": dict(color="tab:red", marker="s"),
         "path+denoise": dict(color="tab:green", marker="^")}


def value(row, key, fallback):
    for k in (key, fallback):
        if k and row.get(k) not in (None, ""):
            v = float(row[k])
            if v > 0:
                return v
    return None


def pareto(points):
    """The points no other point beats in both seconds and error, by seconds."""
    front, best = [], float("inf")
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("-o", "--output")
    ap.add_argument("--title", help="the figure's title (default: the CSV's folder)")
    a = ap.parse_args()
    with open(a.csv) as f:
        rows = list(csv.DictReader(f))
    out = a.output or os.path.join(os.path.dirname(a.csv) or ".", "accuracy_vs_time.png")
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for ax, (key, fallback, title) in zip(axes.flat, PANELS):
        points = []
        for method, style in STYLE.items():
            xs, ys = [], []
            for r in rows:
                y = value(r, key, fallback)
                if r["method"] != method or y is None:
                    continue
                x = float(r["seconds"])
                xs.append(x)
                ys.append(y)
                points.append((x, y, r["config"]))
                label = r["config"].replace("cache_", "").replace("path_", "")
                ax.annotate(label, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=6, color=style["color"])
            if xs:
                order = sorted(range(len(xs)), key=lambda i: xs[i])
                ax.plot([xs[i] for i in order], [ys[i] for i in order], linestyle="-" if method != "cache" else "",
                        label=method, markersize=5, **style)
        front = pareto(points)
        if front:
            ax.plot([p[0] for p in front], [p[1] for p in front], color="black", linewidth=0.8, linestyle="--",
                    marker="o", markerfacecolor="none", markersize=11, label="Pareto front")
        ax.set_xscale("log")
        ax.set_yscale("log")
        # Plain seconds on the time axis; matplotlib's minor labels (3x10^0, 4x10^0, ...) overlap on short ranges.
        ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("seconds (frame, kernel builds excluded)")
        ax.set_ylabel(title)
        ax.set_title(title + (" less the reference's noise" if "less_noise" in key else ""), fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(a.title or f"accuracy against time: {os.path.basename(os.path.dirname(os.path.abspath(a.csv)))}",
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
