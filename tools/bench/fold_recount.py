#!/usr/bin/python3
"""Recounts a remesh's folded triangles without the remesher's own bookkeeping.

The remesher (remesh/refine.cpp, `folded`) judges a triangle by the summed
unit normals of the input at its corners, and a corner that is not an input
vertex (a midpoint, a point on the surface, an untangled site) by the normal
it was given when it was placed. This script judges every corner by the
input vertex nearest to it, so the two counts agree on triangles whose
corners are all input vertices and can differ on the others. It also counts
the triangles that face against the input triangle nearest their centroid.

usage: /usr/bin/python3 tools/bench/fold_recount.py OVERSAMPLED.obj REMESH.obj
  OVERSAMPLED.obj: the remesher's input, made by
    srcodec subdivide MESH -o OVERSAMPLED.obj --scheme butterfly --steps S
  with S the remesh's "oversample_steps" (--json). It is the remesher's own
  input only for a mesh of one clean component (armadillo, stanford-bunny,
  nefertiti, igea, lionstatue); on ogre and beast the cleaning and the
  per-component steps differ, and the counts are approximate.
"""
import sys

import numpy as np
from scipy.spatial import cKDTree


def read_obj(path):
    """Positions and triangles (polygons fanned) of an OBJ file."""
    positions, triangles = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                positions.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                ids = [int(t.split("/")[0]) for t in line.split()[1:]]
                ids = [i - 1 if i > 0 else len(positions) + i for i in ids]
                triangles += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    return np.array(positions, dtype=float), np.array(triangles, dtype=np.int64)


def face_normals(p, t):
    return np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]])


def unit_rows(v):
    n = np.linalg.norm(v, axis=1)
    return v / np.where(n > 0, n, 1)[:, None]


def unit_vertex_normals(p, t):
    """Area-weighted, as the remesher's unit_vertex_normals."""
    fn = face_normals(p, t)
    n = np.zeros_like(p)
    for c in range(3):
        np.add.at(n, t[:, c], fn)
    return unit_rows(n)


def closest_on_triangles(x, a, b, c):
    """Row-wise closest point to x[i] on triangle (a[i], b[i], c[i])."""
    ab, ac = b - a, c - a
    d1, d2 = (ab * (x - a)).sum(1), (ac * (x - a)).sum(1)
    d3, d4 = (ab * (x - b)).sum(1), (ac * (x - b)).sum(1)
    d5, d6 = (ab * (x - c)).sum(1), (ac * (x - c)).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    den = va + vb + vc
    den = np.where(den == 0, 1e-300, den)
    out = a + ab * (vb / den)[:, None] + ac * (vc / den)[:, None]

    def ratio(num, den):
        return num / np.where(den == 0, 1e-300, den)

    edges = [
        ((vc <= 0) & (d1 >= 0) & (d3 <= 0), a, ab, ratio(d1, d1 - d3)),
        ((vb <= 0) & (d2 >= 0) & (d6 <= 0), a, ac, ratio(d2, d2 - d6)),
        ((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0), b, c - b, ratio(d4 - d3, (d4 - d3) + (d5 - d6))),
    ]
    for mask, start, direction, s in edges:
        out[mask] = (start + direction * s[:, None])[mask]
    out[(d1 <= 0) & (d2 <= 0)] = a[(d1 <= 0) & (d2 <= 0)]
    out[(d3 >= 0) & (d4 <= d3)] = b[(d3 >= 0) & (d4 <= d3)]
    out[(d6 >= 0) & (d5 <= d6)] = c[(d6 >= 0) & (d5 <= d6)]
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    pi, ti = read_obj(sys.argv[1])
    po, to = read_obj(sys.argv[2])
    normals = unit_vertex_normals(pi, ti)
    tree = cKDTree(pi)
    dist, nearest = tree.query(po)
    on_input = dist < 1e-12 * max(1.0, np.abs(pi).max())

    # The remesher's facing test: triangle normal against the summed corner
    # normals, over the squared edge lengths; folded at or below 1e-9.
    fn = face_normals(po, to)
    reference = normals[nearest[to]].sum(1)
    scale = sum(np.linalg.norm(po[to[:, i]] - po[to[:, j]], axis=1) ** 2 for i, j in ((0, 1), (1, 2), (2, 0)))
    r = np.linalg.norm(reference, axis=1)
    facing = (fn * reference).sum(1) / np.where(r * scale > 0, r * scale, 1)
    facing[~(r * scale > 0)] = 0.0
    folded = facing <= 1e-9
    all_on = on_input[to].all(1)

    # Against the input triangle nearest the centroid (among those around
    # the 4 input vertices nearest it).
    centroid = po[to].mean(1)
    degree = np.bincount(ti.ravel(), minlength=len(pi))
    ring = -np.ones((len(pi), degree.max()), dtype=np.int64)
    order = np.argsort(ti.ravel(), kind="stable")
    owner = ti.ravel()[order]
    first = np.concatenate([[0], np.cumsum(degree)[:-1]])
    ring[owner, np.arange(len(owner)) - first[owner]] = order // 3
    _, near = tree.query(centroid, k=4)
    best = np.full(len(to), np.inf)
    best_triangle = np.zeros(len(to), dtype=np.int64)
    for k in range(near.shape[1]):
        for j in range(ring.shape[1]):
            t = ring[near[:, k], j]
            valid = t >= 0
            t = np.where(valid, t, 0)
            q = closest_on_triangles(centroid, pi[ti[t, 0]], pi[ti[t, 1]], pi[ti[t, 2]])
            d = np.where(valid, np.linalg.norm(q - centroid, axis=1), np.inf)
            closer = d < best
            best[closer], best_triangle[closer] = d[closer], t[closer]
    against = (unit_rows(fn) * unit_rows(face_normals(pi, ti))[best_triangle]).sum(1) <= 0

    print(f"{sys.argv[2]}: {len(to)} triangles, {int((~on_input).sum())} of {len(po)} vertices off the input")
    print(f"folded by corner normals: {int(folded.sum())} "
          f"({int((folded & all_on).sum())} with every corner an input vertex, {int((folded & ~all_on).sum())} with "
          f"a corner off the input, judged by the input vertex nearest it)")
    print(f"facing against the input triangle nearest the centroid: {int(against.sum())}")


if __name__ == "__main__":
    main()
