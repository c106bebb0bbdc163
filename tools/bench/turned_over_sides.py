#!/usr/bin/python3
"""How much of a mesh's turned-over area may only be a thin sheet seen from its far side.

Judges each triangle of TEST as the visual measure does (tools/measure/visual_difference.h): turned over
when it faces against the REFERENCE triangle nearest its centroid, here among the 24 with the nearest
centroids. Then, for the turned-over ones, it finds the nearest reference triangle facing the test
triangle's way. Where that one lies within a fraction of a reference edge, the reference is a sheet thinner
than that, and the nearest triangle may be its other side. Prints the turned-over share of TEST's area and,
for 0.1 / 0.25 / 0.5 / 1 median reference edges, the share whose same-facing reference lies that close.

usage: /usr/bin/python3 tools/bench/turned_over_sides.py REFERENCE.obj TEST.obj   (docs/visual_measure.md)
"""
import sys

import numpy as np
from scipy.spatial import cKDTree

from mesh_arrays import load_obj, triangle_d2

CANDIDATES = 24


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    p, t = (np.asarray(a) for a in load_obj(sys.argv[1]))
    q, u = (np.asarray(a) for a in load_obj(sys.argv[2]))
    normal_p = np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]])
    normal_q = np.cross(q[u[:, 1]] - q[u[:, 0]], q[u[:, 2]] - q[u[:, 0]])
    area_q = 0.5 * np.linalg.norm(normal_q, axis=1)
    centroid = q[u].mean(1)
    _, cand = cKDTree(p[t].mean(1)).query(centroid, k=CANDIDATES)
    d2 = triangle_d2(centroid[:, None, :], p[t[cand, 0]], p[t[cand, 1]], p[t[cand, 2]])
    rows = np.arange(len(centroid))
    nearest = cand[rows, d2.argmin(1)]
    turned = np.einsum("ij,ij->i", normal_q, normal_p[nearest]) <= 0
    print(f"turned over: {area_q[turned].sum() / area_q.sum():.4%} of the area ({turned.sum()} triangles)")
    same = np.einsum("ijk,ik->ij", normal_p[cand], normal_q) > 0
    same_facing = np.sqrt(np.where(same, d2, np.inf).min(1))[turned]
    edge = np.median(np.linalg.norm(p[t[:, 1]] - p[t[:, 0]], axis=1))
    for fraction in (0.1, 0.25, 0.5, 1.0):
        near = same_facing < fraction * edge
        print(f"  of which a same-facing reference triangle lies within {fraction:g} median reference edges: "
              f"{area_q[turned][near].sum() / area_q.sum():.4%}")


if __name__ == "__main__":
    main()
