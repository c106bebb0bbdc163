#!/usr/bin/python3
"""Recounts a remesh's folded triangles without the remesher's own bookkeeping.

The remesher (remesh/refine.cpp, `folded`) judges a triangle by the summed
unit normals of the input at its corners, and a corner that is not an input
vertex (a midpoint, a point on the surface, an untangled site) by the normal
it was given when it was placed. This script judges every corner by the
input vertex nearest to it, so the two counts agree on triangles whose
corners are all input vertices and can differ on the others. It also counts
the triangles that face against the input triangle nearest their centroid.

usage: /usr/bin/python3 tools/bench/fold_recount.py OVERSAMPLED.obj REMESH.obj [MORE.obj ...]
  (any triangle mesh: a decoded .srm, Draco's decoded mesh; each is recounted, with the share of its area folded)
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

from mesh_arrays import load_obj, nearest_triangle


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


def recount(pi, normals, tree, po, to):
    """The remesher's facing test on mesh po/to against input positions pi (their unit vertex normals, a
    cKDTree over pi), every corner judged by the input vertex nearest it. Returns per triangle whether it is
    folded and whether every corner is an input vertex, per vertex of po whether it is one, and per triangle
    its area."""
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
    return facing <= 1e-9, on_input[to].all(1), on_input, 0.5 * np.linalg.norm(fn, axis=1)


def area_percent(mask, area):
    """The share of the area (per triangle) that the triangles in mask cover, in percent."""
    return 100.0 * area[mask].sum() / max(area.sum(), 1e-300)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    pi, ti = load_obj(sys.argv[1])
    normals = unit_vertex_normals(pi, ti)
    tree = cKDTree(pi)
    for path in sys.argv[2:]:
        po, to = load_obj(path)
        folded, all_on, on_input, area = recount(pi, normals, tree, po, to)
        # Against the input triangle nearest the centroid.
        _, nearest_input = nearest_triangle(po[to].mean(1), pi, ti)
        against = (unit_rows(face_normals(po, to)) * unit_rows(face_normals(pi, ti))[nearest_input]).sum(1) <= 0
        share = area_percent(folded, area)
        print(f"{path}: {len(to)} triangles, {int((~on_input).sum())} of {len(po)} vertices off the input")
        print(f"folded by corner normals: {int(folded.sum())} "
              f"({int((folded & all_on).sum())} with every corner an input vertex, "
              f"{int((folded & ~all_on).sum())} with a corner off the input, judged by the input vertex nearest it), "
              f"{share:.3f}% of the area")
        print(f"facing against the input triangle nearest the centroid: {int(against.sum())}")


if __name__ == "__main__":
    main()
