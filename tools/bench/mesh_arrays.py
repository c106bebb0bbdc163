"""Triangle meshes as numpy arrays, for the benchmark scripts in this folder
(adaptive_bound.py, error_hotspots.py, fold_recount.py): reading OBJ files and finding the
nearest triangle of a mesh to many points."""
import numpy as np
from scipy.spatial import cKDTree


def load_obj(path):
    """Positions (n x 3) and triangles (m x 3, polygons fanned) of an OBJ file."""
    positions, triangles = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                positions.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                ids = [int(x.split("/")[0]) for x in line.split()[1:]]
                ids = [i - 1 if i > 0 else len(positions) + i for i in ids]
                triangles += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    return np.array(positions, dtype=float), np.array(triangles, dtype=np.int64)


def segment_d2(p, a, b):
    ab = b - a
    t = np.clip(((p - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0.0, 1.0)
    return ((p - (a + t[..., None] * ab)) ** 2).sum(-1)


def triangle_d2(p, a, b, c):
    n = np.cross(b - a, c - a)
    nn = np.maximum((n * n).sum(-1), 1e-300)
    d = ((p - a) * n).sum(-1)
    q = p - (d / nn)[..., None] * n
    inside = ((np.cross(b - a, q - a) * n).sum(-1) >= 0) & ((np.cross(c - b, q - b) * n).sum(-1) >= 0) & (
        (np.cross(a - c, q - c) * n).sum(-1) >= 0)
    edges = np.minimum(np.minimum(segment_d2(p, a, b), segment_d2(p, b, c)), segment_d2(p, c, a))
    return np.where(inside, d * d / nn, edges)


def nearest_triangle(points, positions, triangles, k=10, chunk=100000):
    """Squared distance from each point to the mesh and the triangle it is nearest to (among the k triangles
    with the nearest centroids), `chunk` points at a time."""
    tree = cKDTree(positions[triangles].mean(1))
    d2_out = np.empty(len(points))
    owner = np.empty(len(points), dtype=np.int64)
    for start in range(0, len(points), chunk):
        p = points[start:start + chunk]
        _, cand = tree.query(p, k=k)
        d2 = triangle_d2(p[:, None, :], positions[triangles[cand, 0]], positions[triangles[cand, 1]],
                         positions[triangles[cand, 2]])
        best = d2.argmin(1)
        rows = np.arange(len(p))
        d2_out[start:start + chunk] = d2[rows, best]
        owner[start:start + chunk] = cand[rows, best]
    return d2_out, owner
