#!/usr/bin/python3
"""Independent Metro-style surface distance, to check `srcodec compare` against.

    /usr/bin/python3 tools/metro_check.py REF TEST [--samples N] [--seed S] [--json]

Shares no code with srcodec: meshes are read by Open3D (OBJ, PLY, ...), the
surfaces are sampled area-uniformly with NumPy's own generator (faces drawn
i.i.d. in proportion to area, a point uniform in the face), and each sample's
distance to the other surface comes from Open3D's RaycastingScene (Embree's
closest-point query). Embree works in float32, so by default the closest
triangle it reports is re-measured in float64 (closest point on a triangle,
Ericson, Real-Time Collision Detection 5.1.5); --float32 keeps Embree's own
distances instead. Both meshes are first translated by the same vector (the
centre of the reference's bounding box), which leaves every distance unchanged
and keeps float32 coordinates small.

Figures, as srcodec defines them: RMS, mean and max each way; rms = the larger
RMS, hausdorff = the larger max, diag = bounding-box diagonal of REF (all its
vertices), psnr = 20 log10(diag / rms). Zero-area triangles are dropped (they
have no surface), as srcodec does.

Needs Debian's python3-open3d and python3-numpy: run it with /usr/bin/python3,
not a pyenv/venv python that lacks them.
"""

import argparse
import json
import math
import sys
import time

import numpy as np

try:
    import open3d as o3d
except ImportError as error:  # pragma: no cover - environment problem
    sys.exit(f"metro_check: cannot import open3d ({error}); run with /usr/bin/python3 "
             "and install python3-open3d")


def load_mesh(path):
    """Returns (vertices float64 (n,3), triangles int64 (m,3)) as Open3D reads them."""
    mesh = o3d.io.read_triangle_mesh(path)
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    triangles = np.asarray(mesh.triangles, dtype=np.int64)
    if len(vertices) == 0 or len(triangles) == 0:
        raise ValueError(f"{path}: Open3D read no triangles (missing file or unsupported format?)")
    if triangles.min() < 0 or triangles.max() >= len(vertices):
        raise ValueError(f"{path}: a triangle references a vertex out of range")
    if not np.isfinite(vertices[np.unique(triangles)]).all():
        raise ValueError(f"{path}: a vertex used by a triangle has a non-finite coordinate")
    return vertices, triangles


def bbox_diagonal(vertices):
    return float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))


def positive_area_faces(vertices, triangles, path):
    """Drops zero-area triangles; returns (triangles, areas)."""
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    areas = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    keep = areas > 0
    if not keep.any():
        raise ValueError(f"{path}: no triangle of positive area, no surface to measure")
    return triangles[keep], areas[keep]


def sample_surface(vertices, triangles, areas, count, rng):
    """`count` points, i.i.d. uniform in area over the triangles."""
    faces = rng.choice(len(triangles), size=count, p=areas / areas.sum())
    r1 = np.sqrt(rng.random(count))[:, None]
    r2 = rng.random(count)[:, None]
    a, b, c = (vertices[triangles[faces, k]] for k in range(3))
    return (1 - r1) * a + (r1 * (1 - r2)) * b + (r1 * r2) * c


def closest_points_on_triangles(p, a, b, c):
    """Row-wise closest point of p[i] on triangle (a[i], b[i], c[i]), float64.

    Ericson's Voronoi-region walk, vectorised: the regions are tested in his
    order (A, B, AB, C, AC, BC, inside), so here they are written in reverse
    and the first region that holds wins.
    """
    dot = lambda x, y: np.einsum("ij,ij->i", x, y)
    ab, ac = b - a, c - a
    ap, bp, cp = p - a, p - b, p - c
    d1, d2 = dot(ab, ap), dot(ac, ap)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v = (vb / denom)[:, None]
        w = (vc / denom)[:, None]
        out = a + v * ab + w * ac  # inside the triangle
        t = ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None]
        m = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        out[m] = (b + t * (c - b))[m]  # edge BC
        t = (d2 / (d2 - d6))[:, None]
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        out[m] = (a + t * ac)[m]  # edge AC
        m = (d6 >= 0) & (d5 <= d6)
        out[m] = c[m]  # vertex C
        t = (d1 / (d1 - d3))[:, None]
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        out[m] = (a + t * ab)[m]  # edge AB
        m = (d3 >= 0) & (d4 <= d3)
        out[m] = b[m]  # vertex B
        m = (d1 <= 0) & (d2 <= 0)
        out[m] = a[m]  # vertex A
    return out


class Surface:
    """A mesh as an Open3D raycasting scene (float32) plus its float64 triangles."""

    def __init__(self, vertices, triangles):
        self.vertices = vertices
        self.triangles = triangles
        self.scene = o3d.t.geometry.RaycastingScene()
        self.scene.add_triangles(
            o3d.core.Tensor(np.ascontiguousarray(vertices, dtype=np.float32)),
            o3d.core.Tensor(np.ascontiguousarray(triangles, dtype=np.uint32)))

    def distances(self, points, float32_only=False, chunk=1 << 20):
        out = np.empty(len(points), dtype=np.float64)
        for start in range(0, len(points), chunk):
            p = points[start:start + chunk]
            query = o3d.core.Tensor(np.ascontiguousarray(p, dtype=np.float32))
            if float32_only:
                out[start:start + chunk] = self.scene.compute_distance(query).numpy()
                continue
            answer = self.scene.compute_closest_points(query)
            ids = answer["primitive_ids"].numpy().astype(np.int64)
            tri = self.triangles[ids]
            a, b, c = (self.vertices[tri[:, k]] for k in range(3))
            q = closest_points_on_triangles(p, a, b, c)
            out[start:start + chunk] = np.linalg.norm(p - q, axis=1)
        return out


def directed(distances):
    return {
        "rms": float(math.sqrt(np.mean(np.square(distances)))),
        "mean": float(np.mean(distances)),
        "max": float(np.max(distances)),
        "samples": int(len(distances)),
    }


def measure(ref_path, test_path, samples, seed, float32_only=False):
    ref_v, ref_t = load_mesh(ref_path)
    test_v, test_t = load_mesh(test_path)
    diag = bbox_diagonal(ref_v)
    origin = 0.5 * (ref_v.min(axis=0) + ref_v.max(axis=0))
    ref_v, test_v = ref_v - origin, test_v - origin
    ref_t, ref_areas = positive_area_faces(ref_v, ref_t, ref_path)
    test_t, test_areas = positive_area_faces(test_v, test_t, test_path)

    ref_rng, test_rng = (np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(2))
    ref_samples = sample_surface(ref_v, ref_t, ref_areas, samples, ref_rng)
    test_samples = sample_surface(test_v, test_t, test_areas, samples, test_rng)

    ref_to_test = directed(Surface(test_v, test_t).distances(ref_samples, float32_only))
    test_to_ref = directed(Surface(ref_v, ref_t).distances(test_samples, float32_only))
    rms = max(ref_to_test["rms"], test_to_ref["rms"])
    return {
        "reference": ref_path,
        "test": test_path,
        "rms": rms,
        "hausdorff": max(ref_to_test["max"], test_to_ref["max"]),
        "psnr": 20 * math.log10(diag / rms) if rms > 0 else math.inf,
        "diag": diag,
        "ref_to_test": ref_to_test,
        "test_to_ref": test_to_ref,
        "seed": seed,
        "distances": "float32 (Embree)" if float32_only else "float64 (Embree triangle, re-measured)",
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("reference", help="reference mesh (its bounding-box diagonal sets the PSNR scale)")
    parser.add_argument("test", help="mesh to measure against the reference")
    parser.add_argument("--samples", type=int, default=200000, help="area-uniform samples on each surface")
    parser.add_argument("--seed", type=int, default=1, help="NumPy seed for the sampling")
    parser.add_argument("--float32", action="store_true", help="keep Embree's float32 distances")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    if args.samples < 1:
        parser.error("--samples must be at least 1")

    start = time.perf_counter()
    try:
        r = measure(args.reference, args.test, args.samples, args.seed, args.float32)
    except ValueError as error:
        print(f"metro_check: {error}", file=sys.stderr)
        return 1
    r["seconds"] = round(time.perf_counter() - start, 3)

    if args.json:
        # Infinity is not JSON; 1e308 is what srcodec's JSON writer prints for it.
        print(json.dumps({k: (1e308 if v == math.inf else v) for k, v in r.items()}))
        return 0
    line = lambda name, d: print(f"  {name:<12} rms {d['rms']:<12.6g} mean {d['mean']:<12.6g} "
                                 f"max {d['max']:<12.6g} ({d['samples']} samples)")
    print(f"{args.reference} -> {args.test}  [open3d {o3d.__version__}, {r['distances']}]")
    line("ref -> test", r["ref_to_test"])
    line("test -> ref", r["test_to_ref"])
    print(f"  rms {r['rms']:.6g}  hausdorff {r['hausdorff']:.6g}  diag {r['diag']:.6g}  "
          f"psnr {r['psnr']:.2f} dB  ({r['seconds']} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
