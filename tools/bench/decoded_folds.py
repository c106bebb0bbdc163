#!/usr/bin/python3
"""Folded triangles in decoded meshes: srcodec's remesh, its decoded .srm files and Draco's, side by side.

A remesh with no folded triangle can decode to a mesh with many: the coded
coefficients move every vertex a little, and a triangle nearly edge-on to the
input turns over. For MESH this script writes, in a scratch folder:
  - the remesh `srcodec encode` codes (`srcodec remesh` at the same options),
  - `srcodec encode` at its default rate and at the whole stream, decoded,
  - Draco's decoded mesh at the quantization whose PSNR is nearest the default
    rate's and at one bit more,
and recounts each as tools/bench/fold_recount.py does (every corner judged by
the normal of the input vertex nearest it, over the input oversampled as the
remesher oversampled it): folded triangles and their share of the area.

usage: /usr/bin/python3 tools/bench/decoded_folds.py MESH
  MESH: any mesh srcodec reads (OBJ, PLY, OFF, STL)
"""
import os
import sys
import tempfile

from scipy.spatial import cKDTree

from fold_recount import area_percent, recount, unit_vertex_normals
from mesh_arrays import load_obj
from srcodec_cli import draco_point, or_exit, run, run_json


def main():
    args = sys.argv[1:]
    if len(args) != 1:
        sys.exit(__doc__)
    mesh = args[0]
    with tempfile.TemporaryDirectory() as tmp:
        at = lambda name: os.path.join(tmp, name)
        rows = []  # (what, bytes, psnr, path)
        remesh = run_json(["remesh", mesh, "-o", at("remesh.obj"), "--json", "-q"])
        rows.append(("remesh (what encode codes)", "", remesh["levels"][-1]["psnr"], at("remesh.obj")))
        run(["subdivide", mesh, "-o", at("over.obj"), "--scheme", "butterfly",
             "--steps", str(remesh["oversample_steps"])])
        target = None
        for what, rate in (("srcodec, default rate", []), ("srcodec, whole stream", ["--bytes", "1000000000"])):
            srm = at("coded.srm")
            coded = run_json(["encode", mesh, "-o", srm, "--json", "-q"] + rate)
            decoded = at(what.replace(", ", "_").replace(" ", "_") + ".obj")
            run(["decode", srm, "-o", decoded])
            rows.append((what, coded["bytes"], coded["psnr"], decoded))
            target = coded["psnr"] if target is None else target
        draco = []
        for qp in range(6, 31):  # Draco's PSNR grows with qp: two past the target decide both rows
            out = at(f"draco{qp}.obj")
            draco.append((qp, *draco_point(mesh, qp, out), out))
            if len(draco) >= 2 and min(draco[-1][2], draco[-2][2]) > target:
                break
        nearest = min(range(len(draco)), key=lambda i: abs(draco[i][2] - target))
        for qp, size, q, out in draco[nearest:nearest + 2]:
            rows.append((f"Draco qp {qp}", size, q, out))

        pi, ti = load_obj(at("over.obj"))
        normals, tree = unit_vertex_normals(pi, ti), cKDTree(pi)
        print(f"{os.path.basename(mesh)}, oversampled {remesh['oversample_steps']} time(s) for the recount")
        print("| mesh | bytes | PSNR dB | triangles | folded | folded area |")
        print("|---|---:|---:|---:|---:|---:|")
        for what, size, q, path in rows:
            po, to = load_obj(path)
            folded, _, _, area = recount(pi, normals, tree, po, to)
            share = area_percent(folded, area)
            print(f"| {what} | {size} | {q:.2f} | {len(to)} | {int(folded.sum())} | {share:.3f}% |", flush=True)


if __name__ == "__main__":
    or_exit(main)
