#!/usr/bin/python3
"""The issue's first requirement over the whole corpus, at the defaults.

For each corpus mesh: `srcodec remesh MESH -o OUT` with the defaults (or the
options given in REMESH), then `srcodec info` on both. Prints a Markdown
table: components, boundary loops and genus of the cleaned input and of the
output as written (genus only where the surface is manifold), whether they
agree, how many of the output's vertices a reader that welds coincident
positions (as our cleaning does) would merge, and the output's folded
triangles and pleats (finest + coarser levels, the remesher's recount: every
corner judged by the input vertex nearest it) and PSNR.

usage: /usr/bin/python3 tools/bench/corpus_remesh.py [MESH ...]
       REMESH="--levels 5" /usr/bin/python3 tools/bench/corpus_remesh.py armadillo.obj
"""
import os
import shlex
import sys
import tempfile

from srcodec_cli import CORPUS, REMESH_EXPERIMENT, Failed, corpus_meshes, run_json


def shape(info):
    genus = info.get("genus")
    return info["components"], info["boundary_loops"], "-" if genus is None else genus


def main():
    meshes = sys.argv[1:] or corpus_meshes()
    extra = shlex.split(os.environ.get("REMESH", ""))
    print("| mesh | components in, out | boundary loops in, out | genus in, out | same | welded on reading "
          "| finest triangles | PSNR dB | folded | pleats | seconds |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in meshes:
            mesh, out = os.path.join(CORPUS, name), os.path.join(tmp, "out.ply")
            try:
                d = run_json(["remesh", mesh, "-o", out, "--json", "--quiet"] + extra, REMESH_EXPERIMENT)
                src, got = run_json(["info", mesh, "--json"]), run_json(["info", out, "--json"])
            except Failed as e:
                print(f"| {name} | error: {e} ||||||||||", flush=True)
                continue
            a, b = shape(src["cleaned"]), shape(got)
            same = "yes" if a == b else "no"
            welded = got["cleaning"]["welded_vertices"]
            top = d["levels"][-1]
            if d.get("untangle"):  # the output's own recount
                folded = f"{d['untangled_folded_by_nearest_input']} + {d['untangled_coarser_folded_by_nearest_input']}"
                pleats = f"{d['untangled_pleats']} + {d['untangled_coarser_pleats']}"
            else:  # no untangling (--no-fit-surface, --no-untangle): the refinement's count of its last level
                folded = f"{top['folded_by_nearest_input']} + {top['coarse_folded_triangles']}"
                pleats = f"{top['pleats']}"
            print(f"| {name} | {a[0]}, {b[0]} | {a[1]}, {b[1]} | {a[2]}, {b[2]} | {same} | {welded} | {top['triangles']} "
                  f"| {top['psnr']:.2f} | {folded} | {pleats} | {d['seconds']:.1f} |", flush=True)


if __name__ == "__main__":
    main()
