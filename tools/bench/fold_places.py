#!/usr/bin/python3
"""Draws the places where a remesh is left folded, for a person to judge them.

For each of the largest places that `srcodec remesh --json` lists as
`tangled_places`, one row of two pictures from the same view: the input
around the place, and the remesh's finest level there with its folded
triangles in red, drawn over the rest so that none is hidden (every corner
judged by the oversampled input vertex nearest it, as the remesher and
tools/bench/fold_recount.py judge). The view looks
down the mean normal of the input there. The pictures show only the finest
level, which the output file holds; the coarser levels' folds (the JSON's
`coarser_folded`) are not drawn.

usage: /usr/bin/python3 tools/bench/fold_places.py INPUT.obj OVERSAMPLED.obj REMESH.obj REMESH.json OUT.png [--places K]
  OVERSAMPLED.obj: srcodec subdivide INPUT.obj -o OVERSAMPLED.obj --scheme butterfly --steps S, with S the
  JSON's "oversample_steps" (as fold_recount.py says, approximate on meshes the cleaning changes).
  K: how many places to draw, the largest first (default 3).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
from scipy.spatial import cKDTree  # noqa: E402

from fold_recount import recount, unit_vertex_normals  # noqa: E402
from mesh_arrays import load_obj  # noqa: E402


def triangles_near(p, t, centre, reach):
    """The triangles of p/t with every corner within reach of centre."""
    return t[(np.linalg.norm(p[t] - centre, axis=2) < reach).all(1)]


def view_angles(normal):
    """matplotlib's elevation and azimuth (degrees) of a view looking down -normal."""
    n = normal / max(np.linalg.norm(normal), 1e-300)
    return np.degrees(np.arcsin(np.clip(n[2], -1, 1))), np.degrees(np.arctan2(n[1], n[0]))


def draw(ax, p, t, centre, reach, elev_azim, title, marked=None):
    """Triangles t of p in grey-blue; those in `marked` drawn over them in red, seen through the rest."""
    ax.computed_zorder = False
    ax.add_collection3d(Poly3DCollection(p[t], facecolors=(0.7, 0.78, 0.9, 0.85), edgecolors=(0.2, 0.2, 0.2, 0.35),
                                         linewidths=0.2, zorder=1))
    if marked is not None and len(marked):
        ax.add_collection3d(Poly3DCollection(p[marked], facecolors=(0.95, 0.1, 0.1, 0.9), edgecolors=(0.6, 0, 0, 1),
                                             linewidths=1.2, zorder=2))
    for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        set_lim(c - reach, c + reach)
    ax.view_init(*elev_azim)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()
    ax.set_title(title, fontsize=8)


def main():
    args = sys.argv[1:]
    places_wanted = 3
    if "--places" in args:
        i = args.index("--places")
        places_wanted = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 5:
        sys.exit(__doc__)
    input_path, oversampled_path, remesh_path, json_path, out_path = args
    pin, tin = load_obj(input_path)
    pov, tov = load_obj(oversampled_path)
    po, to = load_obj(remesh_path)
    places = json.load(open(json_path)).get("tangled_places", [])[:places_wanted]
    if not places:
        sys.exit(f"{json_path}: no tangled_places (a remesh left untangled, or not written by remesh --json)")
    normals = unit_vertex_normals(pov, tov)
    folded = recount(pov, normals, cKDTree(pov), po, to)[0]
    input_normals = unit_vertex_normals(pin, tin)
    input_tree = cKDTree(pin)
    centroid_tree = cKDTree(po[to].mean(1))
    fig = plt.figure(figsize=(8, 4 * len(places)))
    for row, place in enumerate(places):
        centre = np.array([place["x"], place["y"], place["z"]])
        # Far enough to show the place's spread and six of the remesh's edges
        # around it (their median over the triangles there, or the 20 nearest
        # a place of one tangle).
        near = set(centroid_tree.query_ball_point(centre, place["radius"]))
        near.update(np.atleast_1d(centroid_tree.query(centre, k=min(20, len(to)))[1]).tolist())
        near = to[sorted(near)]
        edge = np.median(np.linalg.norm(po[near[:, 0]] - po[near[:, 1]], axis=1))
        reach = max(1.5 * place["radius"], 6 * edge, 1e-6)
        mean_normal = input_normals[input_tree.query_ball_point(centre, reach)].sum(0)
        angles = view_angles(mean_normal)
        tin_near = triangles_near(pin, tin, centre, reach)
        keep = (np.linalg.norm(po[to] - centre, axis=2) < reach).all(1)
        where = f"({place['x']:.1f}, {place['y']:.1f}, {place['z']:.1f})"
        draw(fig.add_subplot(len(places), 2, 2 * row + 1, projection="3d"), pin, tin_near, centre, reach, angles,
             f"input within {reach:.1f} of {where}")
        draw(fig.add_subplot(len(places), 2, 2 * row + 2, projection="3d"), po, to[keep], centre, reach, angles,
             f"finest level: {int(folded[keep].sum())} folded (red); place: {place['folded']} + "
             f"{place['coarser_folded']} folded, {place['pleats']} + {place['coarser_pleats']} pleats",
             to[keep & folded])
    fig.tight_layout()
    fig.savefig(out_path, dpi=80)
    print(f"{out_path}: {len(places)} places")


if __name__ == "__main__":
    main()
