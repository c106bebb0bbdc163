#!/usr/bin/python3
"""Where a remesh's error against its input sits: the worst samples, grouped.

The PSNR of `srcodec compare` comes from the RMS of the larger of the two
one-sided distances. This script samples both surfaces the same way (area-
uniform points, each measured exactly to the nearest of the 40 triangles of
the other surface whose centroids are nearest it), and for each direction
prints its RMS and PSNR, the share of the squared error carried by the worst
1% of the samples, and the worst samples grouped into places (single linkage
at 1% of the input's bounding-box diagonal): each place's share of the
squared error, centre, samples and largest distance, and the PSNR the
direction would have without it. One bad place (a bridge across a cleft, a
part of a hole covered) can hold most of the error of a whole remesh.

usage: /usr/bin/python3 tools/bench/error_hotspots.py INPUT.obj REMESH.obj [SAMPLES] [SEED]
  SAMPLES per surface (default 400000), SEED (default 1). OBJ files only
  (igea: igea_tri.obj).
"""
import sys

import numpy as np
from scipy.cluster.hierarchy import fcluster, linkage

from mesh_arrays import load_obj, nearest_triangle

WORST_FRACTION = 0.01  # the "worst 1%" share
GROUPED = 3000         # worst samples grouped into places
PLACES = 6             # places printed per direction
CANDIDATES = 40        # triangles (nearest centroids first) searched per sample


def triangle_areas(positions, triangles):
    a, b, c = (positions[triangles[:, k]] for k in range(3))
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def checked_obj(path):
    """load_obj, with a one-line error naming the file for what the sampling cannot use."""
    try:
        positions, triangles = load_obj(path)
    except (ValueError, IndexError) as e:
        raise ValueError(f"{path}: {e}") from e
    if len(triangles) == 0:
        raise ValueError(f"{path}: no triangles")
    if triangles.min() < 0 or triangles.max() >= len(positions):
        raise ValueError(f"{path}: a face uses a vertex the file does not have")
    if not np.isfinite(positions[np.unique(triangles)]).all():
        raise ValueError(f"{path}: a vertex of a face has a non-finite coordinate")
    if not triangle_areas(positions, triangles).sum() > 0:
        raise ValueError(f"{path}: no triangle has an area")
    return positions, triangles


def surface_samples(positions, triangles, n, rng):
    a, b, c = (positions[triangles[:, k]] for k in range(3))
    area = triangle_areas(positions, triangles)
    pick = rng.choice(len(triangles), size=n, p=area / area.sum())
    r = rng.random((n, 2))
    flip = r.sum(1) > 1
    r[flip] = 1 - r[flip]
    return a[pick] + r[:, :1] * (b[pick] - a[pick]) + r[:, 1:] * (c[pick] - a[pick])


def psnr(rms, diag):
    return 20 * np.log10(diag / rms) if rms > 0 else float("inf")


def report(name, points, d2, diag):
    total = d2.sum()
    rms = np.sqrt(d2.mean())
    if not total > 0:
        print(f"{name}: every sample lies on the other surface")
        return
    order = np.argsort(-d2)
    worst = order[:max(1, int(WORST_FRACTION * len(d2)))]
    print(f"{name}: rms {rms:.4g}, psnr {psnr(rms, diag):.2f} dB; "
          f"the worst {WORST_FRACTION:.0%} of the samples hold {d2[worst].sum() / total:.0%} of the squared error")
    top = order[:min(GROUPED, len(d2))]
    labels = fcluster(linkage(points[top], "single"), 0.01 * diag, "distance")
    places = []
    for label in np.unique(labels):
        members = top[labels == label]
        share = d2[members].sum() / total
        places.append((share, points[members].mean(0), len(members), np.sqrt(d2[members].max()), members))
    places.sort(key=lambda p: -p[0])
    for share, centre, count, largest, members in places[:PLACES]:
        rest = np.sqrt(max(total - d2[members].sum(), 0.0) / len(d2))
        print(f"  {share:6.1%} at ({centre[0]:.4g}, {centre[1]:.4g}, {centre[2]:.4g}): {count} samples, "
              f"largest {largest:.3g}; without it {psnr(rest, diag):.2f} dB")


def main():
    if len(sys.argv) not in (3, 4, 5):
        sys.exit(__doc__)
    try:
        samples = int(sys.argv[3]) if len(sys.argv) > 3 else 400000
        seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1
        if samples < 1000:
            raise ValueError(f"SAMPLES is {samples}; use at least 1000")
        ip, it = checked_obj(sys.argv[1])
        rp, rt = checked_obj(sys.argv[2])
    except (OSError, ValueError, IndexError) as e:
        sys.exit(f"error: {e}")
    used = ip[np.unique(it)]
    diag = np.linalg.norm(used.max(0) - used.min(0))
    rng = np.random.default_rng(seed)
    on_remesh = surface_samples(rp, rt, samples, rng)
    on_input = surface_samples(ip, it, samples, rng)
    report("remesh -> input", on_remesh, nearest_triangle(on_remesh, ip, it, k=CANDIDATES)[0], diag)
    report("input -> remesh", on_input, nearest_triangle(on_input, rp, rt, k=CANDIDATES)[0], diag)


if __name__ == "__main__":
    main()
