#!/usr/bin/python3
"""Draws the rate-distortion plot of `srcodec rd`: PSNR against bits per input
vertex (log scale) for every codec in rd.csv. Run with Debian's python3 and
python3-matplotlib: rd_plot.py DIR/rd.csv -o DIR/rd.png [--title NAME]."""

import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

STYLES = {"srcodec": ("tab:blue", "o"), "draco": ("tab:orange", "s")}


def read_curves(path):
    """{codec: [(bpv, psnr, setting)]} sorted by rate; infinite PSNRs dropped."""
    curves = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            bpv, psnr = float(row["bpv"]), float(row["psnr"])
            if bpv > 0 and math.isfinite(psnr):
                curves.setdefault(row["codec"], []).append((bpv, psnr, row["setting"]))
    for points in curves.values():
        points.sort()
    return curves


def draw(curves, title, out):
    fig, ax = plt.subplots(figsize=(7, 5), dpi=120)
    for codec, points in sorted(curves.items()):
        color, marker = STYLES.get(codec, (None, "^"))
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        ax.plot(xs, ys, marker=marker, color=color, label=codec, linewidth=1.5, markersize=4)
        if codec == "draco":  # the quantization bits beside each Draco point
            for x, y, setting in points:
                ax.annotate(setting.replace("qp=", ""), (x, y), textcoords="offset points",
                            xytext=(4, -9), fontsize=7, color=color)
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("rate (bits per input vertex, log scale)")
    ax.set_ylabel("PSNR (dB, bounding-box diagonal / RMS surface distance)")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("csv", help="rd.csv written by srcodec rd")
    parser.add_argument("-o", "--output", required=True, help="image to write (.png or .svg)")
    parser.add_argument("--title", default="rate-distortion")
    args = parser.parse_args()
    curves = read_curves(args.csv)
    if not curves:
        sys.exit(f"rd_plot.py: {args.csv} has no point with a positive rate and a finite PSNR")
    draw(curves, args.title, args.output)


if __name__ == "__main__":
    main()
