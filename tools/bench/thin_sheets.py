#!/usr/bin/python3
"""How much of an input lies closer to a sheet facing the other way than one
edge of a remesh's finest level: the part a remesh at that resolution cannot
separate into its two sheets (lips, flaps, layered cloth), where triangles
bridge the sheets and the fold tests lose their meaning.

For every input vertex used by a face: is there another input vertex within
half an edge / one edge (the remesh's median edge length) whose area-weighted
normal is more than 120 degrees from its own? Prints the fractions.

usage: /usr/bin/python3 tools/bench/thin_sheets.py INPUT.obj REMESH.obj
  e.g. srcodec remesh ../shared/data/meshes/beast.obj -o /tmp/b.obj
       tools/bench/thin_sheets.py ../shared/data/meshes/beast.obj /tmp/b.obj
"""
import sys

import numpy as np
from scipy.spatial import cKDTree

from fold_recount import unit_vertex_normals
from mesh_arrays import load_obj


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    pi, ti = load_obj(sys.argv[1])
    po, to = load_obj(sys.argv[2])
    used = np.unique(ti)
    normals = unit_vertex_normals(pi, ti)
    edge = np.median(np.linalg.norm(po[to[:, 0]] - po[to[:, 1]], axis=1))
    tree = cKDTree(pi[used])
    fractions = []
    for radius in (0.5 * edge, edge):
        pairs = tree.query_pairs(radius, output_type="ndarray")
        a, b = used[pairs[:, 0]], used[pairs[:, 1]]
        facing_apart = (normals[a] * normals[b]).sum(1) < -0.5
        near_sheet = np.zeros(len(pi), dtype=bool)
        near_sheet[a[facing_apart]] = True
        near_sheet[b[facing_apart]] = True
        fractions.append(100.0 * near_sheet.sum() / len(used))
    print(f"{sys.argv[1]}: finest edge {edge:.4g}; input vertices with one facing the other way within half an edge: "
          f"{fractions[0]:.2f}%, within one edge: {fractions[1]:.2f}%")


if __name__ == "__main__":
    main()
