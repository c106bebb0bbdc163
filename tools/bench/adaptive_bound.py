#!/usr/bin/python3
"""How few triangles an adaptive last level could keep at all: a bound for the
"within 0.5 dB of uniform with at most 60% of its triangles" target.

Takes a uniform remesh's last two levels (written by `srcodec remesh ... --uniform
--write-levels PREFIX`) and the input. Each input vertex's squared distance to
the coarser level (C) and to the finest (F) is summed per nearest triangle of C:
leaving that triangle unsplit keeps its C error, splitting it gives its F error.
Splitting C's triangles in the best order (by their own gain), how many
triangles does the finest level need to stay within 0.5 dB of uniform F?
Without closure, and with the remesher's red-green closure (a triangle with two
or three split neighbours is split too, one with one split neighbour becomes two
green triangles). The error is one-sided (input to remesh), not the symmetric
PSNR of `srcodec compare`.

Also with a lighter closure than the remesher's, for comparison: a triangle with
two split neighbours becomes three triangles instead of being split ("blue").
With a fourth mesh, the level below COARSER, also the best choice over two
adaptive levels without closure: each triangle of that level stays, or is split
and each of its four children stays or is split (children found by centroid).

usage: /usr/bin/python3 tools/bench/adaptive_bound.py INPUT.obj COARSER.obj FINEST.obj [BELOW.obj]
  e.g. srcodec remesh igea.ply -o /tmp/i.obj --levels 5 --uniform --write-levels /tmp/i
       tools/bench/adaptive_bound.py ../shared/data/meshes/igea_tri.obj /tmp/i_l4.obj /tmp/i_l5.obj /tmp/i_l3.obj
"""
import sys
from collections import defaultdict

import numpy as np

from mesh_arrays import load_obj, nearest_triangle


def neighbours(triangles):
    by_edge = defaultdict(list)
    for t, (a, b, c) in enumerate(triangles):
        for u, v in ((a, b), (b, c), (c, a)):
            by_edge[(min(u, v), max(u, v))].append(t)
    out = np.full((len(triangles), 3), -1)
    fill = np.zeros(len(triangles), dtype=int)
    for ts in by_edge.values():
        if len(ts) == 2:
            for x, y in ((ts[0], ts[1]), (ts[1], ts[0])):
                out[x, fill[x]] = y
                fill[x] += 1
    return out


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    inputs, _ = load_obj(sys.argv[1])
    coarse_v, coarse_t = load_obj(sys.argv[2])
    fine_v, fine_t = load_obj(sys.argv[3])
    d_coarse, owner = nearest_triangle(inputs, coarse_v, coarse_t)
    d_fine, owner_fine = nearest_triangle(inputs, fine_v, fine_t)
    n = len(coarse_t)
    e_coarse = np.bincount(owner, weights=d_coarse, minlength=n)
    e_fine = np.bincount(owner, weights=d_fine, minlength=n)
    gain = e_coarse - e_fine
    target = d_fine.sum() * 10 ** 0.05  # 0.5 dB above uniform's squared error
    uniform = len(fine_t)
    print(f"coarser level: {n} triangles, finest: {uniform}; one-sided RMS {np.sqrt(d_coarse.mean()):.4g} -> "
          f"{np.sqrt(d_fine.mean()):.4g}")

    order = np.argsort(-gain)
    remaining = e_coarse.sum() - np.cumsum(gain[order])
    k = int(np.argmax(remaining <= target)) + 1
    print(f"best order, no closure: split {k} ({100 * k / n:.1f}%) -> {100 * (n + 3 * k) / uniform:.1f}% of "
          f"uniform's triangles")

    around = neighbours(coarse_t)

    def closed(selected, red_at=2):
        selected = selected.copy()
        while True:
            split_around = np.where(around >= 0, selected[np.maximum(around, 0)], False).sum(1)
            more = ~selected & (split_around >= red_at)
            if not more.any():
                break
            selected |= more
        triangles = 4 * selected.sum() + ((~selected) * (1 + split_around)).sum()
        return triangles, e_coarse[~selected].sum() + e_fine[selected].sum()

    for name, score, red_at in (("gain", gain, 2), ("error mass", e_coarse, 2), ("gain", gain, 3)):
        order = np.argsort(-score)
        lo, hi = 0, n
        while lo < hi:  # the fewest splits, in this order, whose closure meets the target
            mid = (lo + hi) // 2
            selected = np.zeros(n, dtype=bool)
            selected[order[:mid]] = True
            if closed(selected, red_at)[1] <= target:
                hi = mid
            else:
                lo = mid + 1
        selected = np.zeros(n, dtype=bool)
        selected[order[:lo]] = True
        triangles, _ = closed(selected, red_at)
        closure = "with closure" if red_at == 2 else "with the lighter (blue) closure"
        print(f"order by {name}, {closure}: {lo} selected -> {100 * triangles / uniform:.1f}% of uniform's "
              f"triangles")

    if len(sys.argv) == 5:
        below = load_obj(sys.argv[4])
        two_level_bound(inputs, below, (coarse_v, coarse_t), (fine_v, fine_t), nearest_triangle(inputs, *below)[0],
                        d_coarse, d_fine, owner_fine, target)


def two_level_bound(inputs, below, coarser, finest, d_below, d_coarse, d_fine, owner_fine, target):
    """The fewest triangles over two adaptive levels, no closure: for a Lagrange multiplier lam, each triangle
    of BELOW takes the cheaper of staying (1 + lam * error) and being split, its children each the cheaper of
    staying and being split; lam grows until the error meets the target. d_*: each input vertex's squared
    distance to that level; owner_fine: its nearest triangle of FINEST."""
    def parent(child, mesh):
        return nearest_triangle(child[0][child[1]].mean(1), mesh[0], mesh[1])[1]
    up_fine, up_coarse = parent(finest, coarser), parent(coarser, below)
    owner = up_fine[owner_fine]  # each input vertex counted under the same ancestors at every level
    n_below, n_coarse = len(below[1]), len(coarser[1])
    e_below = np.bincount(up_coarse[owner], weights=d_below, minlength=n_below)
    e_coarse = np.bincount(owner, weights=d_coarse, minlength=n_coarse)
    e_fine = np.bincount(owner, weights=d_fine, minlength=n_coarse)
    for lam in np.logspace(0, 16, 800) / max(d_fine.mean(), 1e-300) / len(inputs):
        split_child = 4 + lam * e_fine < 1 + lam * e_coarse
        child_cost = np.where(split_child, 4 + lam * e_fine, 1 + lam * e_coarse)
        split = np.bincount(up_coarse, weights=child_cost, minlength=n_below) < 1 + lam * e_below
        child_triangles = np.bincount(up_coarse, weights=np.where(split_child, 4, 1), minlength=n_below)
        child_error = np.bincount(up_coarse, weights=np.where(split_child, e_fine, e_coarse), minlength=n_below)
        if np.where(split, child_error, e_below).sum() <= target:
            triangles = np.where(split, child_triangles, 1).sum()
            print(f"two adaptive levels, no closure: {100 * triangles / len(finest[1]):.1f}% of uniform's triangles "
                  f"({100 * split.mean():.1f}% of the level below split)")
            return
    print("two adaptive levels: the target was not met")


if __name__ == "__main__":
    main()
