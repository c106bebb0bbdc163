#!/usr/bin/python3
"""Draws the rate-distortion plot of `srcodec rd`: for every codec in rd.csv,
PSNR against bits per input vertex (log scale), and when rd.csv has the
visual measure's columns (tools/measure/visual_difference.h), the same rate
against the depth-map PSNR, the mean normal angle, the share of pixels with
visible defects and the share of the area turned over. Run with Debian's
python3 and python3-matplotlib: rd_plot.py DIR/rd.csv -o DIR/rd.png [--title NAME]."""

import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

STYLES = {"srcodec": ("tab:blue", "o"), "draco": ("tab:orange", "s")}

# (column, axis label, scale applied to the value, log y axis): the panels after the PSNR one.
VISUAL = [
    ("depth_psnr", "depth-map PSNR (dB)", 1.0, False),
    ("normal_deg", "mean normal angle (degrees)", 1.0, True),
    ("defect_share", "visible defects (% of pixels, normals > 30 degrees apart)", 100.0, True),
    ("turned_over_share", "turned over (% of the surface's area)", 100.0, False),
]


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def read_curves(path):
    """{codec: [row]} sorted by rate, each row a dict of floats plus its setting; rows with a
    non-positive rate or an infinite PSNR dropped."""
    curves = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            point = {k: number(v) for k, v in row.items() if k not in ("codec", "setting")}
            point["setting"] = row["setting"]
            if point["bpv"] > 0 and math.isfinite(point["psnr"]):
                curves.setdefault(row["codec"], []).append(point)
    for points in curves.values():
        points.sort(key=lambda p: p["bpv"])
    return curves


def has_column(curves, column):
    return any(math.isfinite(p.get(column, math.nan)) for points in curves.values() for p in points)


def rate_axis(ax):
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("rate (bits per input vertex, log scale)")
    ax.grid(True, which="both", alpha=0.3)


def plot_column(ax, curves, column, scale, label_draco):
    for codec, points in sorted(curves.items()):
        color, marker = STYLES.get(codec, (None, "^"))
        kept = [p for p in points if math.isfinite(p.get(column, math.nan))]
        xs = [p["bpv"] for p in kept]
        ys = [scale * p[column] for p in kept]
        ax.plot(xs, ys, marker=marker, color=color, label=codec, linewidth=1.5, markersize=4)
        if label_draco and codec == "draco":  # the quantization bits beside each Draco point
            for x, y, p in zip(xs, ys, kept):
                ax.annotate(p["setting"].replace("qp=", ""), (x, y), textcoords="offset points",
                            xytext=(4, -9), fontsize=7, color=color)


def draw(curves, title, out):
    panels = [v for v in VISUAL if has_column(curves, v[0])]
    if panels:
        fig, axes = plt.subplots(2, 3, figsize=(16, 9), dpi=110)
        axes = axes.ravel()
    else:
        fig, ax = plt.subplots(figsize=(7, 5), dpi=120)
        axes = [ax]
    plot_column(axes[0], curves, "psnr", 1.0, True)
    axes[0].set_ylabel("PSNR (dB, bounding-box diagonal / RMS surface distance)")
    axes[0].set_title(title)
    axes[0].legend(loc="lower right")
    for ax, (column, label, scale, log) in zip(axes[1:], panels):
        plot_column(ax, curves, column, scale, False)
        ax.set_ylabel(label)
        if log:
            ax.set_yscale("symlog", linthresh=0.01 if scale == 1.0 else 0.001)
    for ax in axes[: 1 + len(panels)]:
        rate_axis(ax)
    for ax in axes[1 + len(panels):]:
        ax.axis("off")
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
