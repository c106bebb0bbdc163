#!/usr/bin/python3
"""Compares two rd reports (tools/rd_corpus.py output folders) mesh by mesh.

For each mesh in both: the rate change of NEW's srcodec curve against OLD's
over the PSNR range both cover, and srcodec against Draco, OLD's curve and
NEW's, over the one range all three curves (OLD, NEW, Draco) cover.
A rate change is the mean difference of log bytes at equal PSNR
(piecewise-linear interpolation of each curve's upper hull: the fewest bytes
for each PSNR), as exp(mean) - 1; negative: NEW needs fewer bytes. The
report's own BD-rate (srcodec rd) fits cubics over each report's own shared
range, which changes when a curve reaches higher: this script holds the range.

usage: /usr/bin/python3 tools/bench/rd_compare.py OLD_DIR NEW_DIR
  e.g. mkdir -p /tmp/old && git archive 859290b docs/rd | tar -x -C /tmp/old
       /usr/bin/python3 tools/bench/rd_compare.py /tmp/old/docs/rd docs/rd
"""
import csv
import os
import sys

import numpy as np


def curve(path, codec):
    """log(bytes) and PSNR of `codec`'s points, the upper hull, by increasing bytes."""
    rows = [r for r in csv.DictReader(open(path)) if r["codec"] == codec]
    points = sorted((float(r["bytes"]), float(r["psnr"])) for r in rows)
    log_bytes, psnr = [], []
    for b, q in points:
        if not psnr or q > psnr[-1]:
            log_bytes.append(np.log(b))
            psnr.append(q)
    return np.array(log_bytes), np.array(psnr)


def rate_change(reference, test, lo, hi):
    """exp(mean(log bytes of test - of reference)) - 1 over PSNR lo..hi; None if either does not cover it."""
    (lr, qr), (lt, qt) = reference, test
    if not (hi > lo) or qr.min() > lo or qt.min() > lo or qr.max() < hi or qt.max() < hi:
        return None
    grid = np.linspace(lo, hi, 200)
    return float(np.exp(np.mean(np.interp(grid, qt, lt) - np.interp(grid, qr, lr))) - 1.0)


def pct(x):
    return "n/a" if x is None else f"{100 * x:+.1f}%"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    old_dir, new_dir = sys.argv[1:]
    changes, old_vs_draco, new_vs_draco = [], [], []
    print("| mesh | NEW against OLD | over PSNR | OLD against Draco | NEW against Draco | over PSNR (all three) |")
    print("|---|---:|---|---:|---:|---|")
    for mesh in sorted(os.listdir(new_dir)):
        new_csv, old_csv = os.path.join(new_dir, mesh, "rd.csv"), os.path.join(old_dir, mesh, "rd.csv")
        if not (os.path.isfile(new_csv) and os.path.isfile(old_csv)):
            continue
        old, new, draco = curve(old_csv, "srcodec"), curve(new_csv, "srcodec"), curve(old_csv, "draco")
        lo, hi = max(old[1].min(), new[1].min()), min(old[1].max(), new[1].max())
        change = rate_change(old, new, lo, hi)
        # Both against Draco over the one range all three curves cover.
        nlo = max(old[1].min(), new[1].min(), draco[1].min())
        dhi = min(old[1].max(), new[1].max(), draco[1].max())
        o, n = rate_change(draco, old, nlo, dhi), rate_change(draco, new, nlo, dhi)
        for values, x in ((changes, change), (old_vs_draco, o), (new_vs_draco, n)):
            if x is not None:
                values.append(x)
        print(f"| {mesh} | {pct(change)} | {lo:.1f}..{hi:.1f} dB | {pct(o)} | {pct(n)} | {nlo:.1f}..{dhi:.1f} dB |")
    med = lambda v: float(np.median(v)) if v else None
    print(f"\nMedians: NEW against OLD {pct(med(changes))} ({len(changes)} meshes); against Draco: "
          f"OLD {pct(med(old_vs_draco))}, NEW {pct(med(new_vs_draco))}")


if __name__ == "__main__":
    main()
