#!/usr/bin/python3
"""Runs `srcodec info --json` over every mesh of a folder and writes a Markdown table.

usage: tools/corpus_info.py [MESH_DIR] > docs/corpus_info.md
"""
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
srcodec = os.path.join(here, "..", "build", "tools", "srcodec")
folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "shared", "data", "meshes")

rows = []
for name in sorted(os.listdir(folder)):
    if os.path.splitext(name)[1].lower() not in (".obj", ".off", ".ply", ".stl"):
        continue
    run = subprocess.run([srcodec, "info", "--json", os.path.join(folder, name)], capture_output=True, text=True)
    if run.returncode != 0:
        rows.append(f"| {name} | error: {run.stderr.strip()} |" + " |" * 10)
        continue
    r = json.loads(run.stdout)
    c = r["cleaned"]
    cl = r["cleaning"]
    genus = lambda d: "n/a" if d["genus"] is None else str(d["genus"])
    faces = "tri" if r["all_triangles"] else f"poly (max {r['max_face_size']})"
    rows.append(
        f"| {name} | {r['vertices']} | {r['faces']} {faces} | {r['components']} | {r['boundary_loops']} | "
        f"{r['nonmanifold_edges']} / {r['nonmanifold_vertices']} | {r['degenerate_faces']} | {genus(r)} | "
        f"{r['bbox_diagonal']:.6g} | {c['vertices']} / {c['faces']} | {c['boundary_loops']} | "
        f"{c['nonmanifold_edges']} / {c['nonmanifold_vertices']} | {genus(c)} | "
        f"{cl['welded_vertices']} welded, {cl['unreferenced_vertices']} unref., {cl['polygons_triangulated']} polys |")

print("# `srcodec info` over the corpus\n")
print("Made by `tools/corpus_info.py ../shared/data/meshes > docs/corpus_info.md`. "
      "\"As read\" is the file as written; \"cleaned\" is what srcodec works on after exact welding, "
      "dropping unreferenced vertices and degenerate or duplicate faces, and triangulating polygons.\n")
print("| file | V | F | comps | bnd loops | nm edges / verts | degen. | genus | bbox diag "
      "| cleaned V / F | cleaned bnd loops | cleaned nm e / v | cleaned genus | cleaning |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
print("\n".join(rows))
