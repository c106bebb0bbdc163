#!/usr/bin/python3
"""Remeshing quality and speed benchmark (issue: adaptive Voronoi remeshing).

For each smooth scan: uniform remeshing to 4 and 5 levels with the default
options, then adaptive remeshing (5 levels) at several Eq. 5 thresholds and
geometric tolerances (--tolerance, within 2 dB of uniform L5's PSNR) and
measured losses (--max-loss); the finest level's PSNR against the input, its triangle count, wall time and peak
memory (from /usr/bin/time). Prints a Markdown table.

usage: /usr/bin/python3 tools/bench/remesh_quality.py [MESH ...] > OUT.md
       THRESHOLDS= TOLERANCE_OFFSETS=-2,-1 NO_HEADER=1 .../remesh_quality.py igea.ply   (rows only, a sweep)
       THRESHOLDS= TOLERANCE_OFFSETS= MAX_LOSSES=0.5,0.7 NO_HEADER=1 .../remesh_quality.py   (uniform and --max-loss rows)
"""
import json
import os
import re
import subprocess
import sys
import tempfile

from srcodec_cli import CORPUS, REMESH_EXPERIMENT, failure

MESHES = ["stanford-bunny.obj", "armadillo.obj", "nefertiti.obj", "igea.ply"]

def int_list(name, default):
    """A comma-separated list of integers from the environment (may be empty), else `default`."""
    value = os.environ.get(name)
    return default if value is None else [int(x) for x in value.split(",") if x.strip()]


# Environment overrides for sweeps: THRESHOLDS=4,8 TOLERANCE_OFFSETS=-2,-1 MAX_LOSSES=0.5 (empty skips those rows).
THRESHOLDS = int_list("THRESHOLDS", [4, 8, 16])
TOLERANCE_OFFSETS = int_list("TOLERANCE_OFFSETS", [-2, 0, 2])
MAX_LOSSES = [x.strip() for x in os.environ.get("MAX_LOSSES", "0.5").split(",") if x.strip()]


def run(mesh, extra):
    with tempfile.TemporaryDirectory() as tmp:
        args = ["remesh", os.path.join(CORPUS, mesh), "-o", os.path.join(tmp, "out.ply"), "--json", "--quiet"] + extra
        timing = os.path.join(tmp, "time.txt")  # kept apart from srcodec's stderr, whose last line says what failed
        print(" ".join([REMESH_EXPERIMENT] + args), file=sys.stderr, flush=True)
        p = subprocess.run(["/usr/bin/time", "-v", "-o", timing, REMESH_EXPERIMENT] + args, capture_output=True,
                           text=True)
        if p.returncode != 0:
            return None, str(failure(args, p.returncode, p.stderr))
        with open(timing) as f:
            times = f.read()
        rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", times).group(1))
        wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", times).group(1)
        secs = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.split(":"))))
        d = json.loads(p.stdout)
        d["wall"] = secs
        d["rss_mb"] = rss / 1024
        return d, None


def main():
    meshes = sys.argv[1:] or MESHES
    if os.environ.get("NO_HEADER"):
        return table(meshes)
    print("# Remeshing quality and speed")
    print()
    print("Made by `/usr/bin/python3 tools/bench/remesh_quality.py > OUT.md` on the 2-core CI-like")
    print("machine. PSNR of the finest level against the input (srcodec compare, 200k samples per surface); wall time")
    print("and peak memory of the whole `srcodec remesh` run, error measurement included. Default base size and")
    print("`--oversample auto`. Adaptive runs use 5 levels: \"eps\" rows the paper's criterion (`--threshold`),")
    print("\"geometric\" rows `--uniform --tolerance` at TOLERANCE_OFFSETS dB (default -2, 0, 2) from uniform L5's PSNR,")
    print("\"measured\" rows `--max-loss` at MAX_LOSSES dB (default 0.5).")
    print("\"tri %\" and \"vs L5\" are the triangle count and the PSNR relative to uniform 5 levels. \"folded\": triangles")
    print("facing against the input surface, on the finest level + on the coarser ones; \"pleats\": edges of the finest")
    print("level whose two triangles meet at more than 150 degrees. The goal for both is 0. \"recount\": the finest")
    print("level's folded triangles with every corner judged by the input vertex nearest it (the JSON's")
    print("folded_by_nearest_input; \"folded\" judges a corner off the input by the normal it was given). The fit to")
    print("the input surface (on by default) runs last: \"folded\" is counted before it, \"recount\" and \"pleats\"")
    print("after it (fit_folded_by_nearest_input, fit_pleats), and for \"measured\" rows after the coarsening that")
    print("follows the fit (coarsened_folded_by_nearest_input, coarsened_pleats). With the untangling (on by default,")
    print("after the fit and the coarsening) \"recount\" and \"pleats\" are the")
    print("output's, finest level + coarser levels (untangled_folded_by_nearest_input, untangled_pleats and their")
    print("coarser_ counterparts).")
    print()
    print("| mesh | run | base | oversampled | finest vertices | triangles | tri % | PSNR dB | vs L5 dB | folded "
          "| recount | pleats | seconds | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    table(meshes)


def table(meshes):
    for mesh in meshes:
        uniform5 = None
        runs = [("uniform L4", ["--levels", "4", "--uniform"]), ("uniform L5", ["--levels", "5", "--uniform"])]
        runs += [(f"adaptive L5 eps={t}", ["--levels", "5", "--threshold", str(t)]) for t in THRESHOLDS]
        # The geometric criterion at tolerances near uniform L5's
        # PSNR (known only once that row has run).
        runs += [(f"geometric L5 uniform{k:+d}", k) for k in TOLERANCE_OFFSETS]
        runs += [(f"measured L5 loss={x} dB", ["--levels", "5", "--max-loss", x]) for x in MAX_LOSSES]
        for name, extra in runs:
            if isinstance(extra, int):
                if uniform5 is None:
                    continue
                tol = round(uniform5["psnr"] + extra)
                name = f"geometric L5 tol={tol} dB"
                extra = ["--levels", "5", "--uniform", "--tolerance", str(tol)]
            d, err = run(mesh, extra)
            if d is None:
                print(f"| {mesh} | {name} | error: {err} ||||||||||||")
                continue
            top = d["levels"][-1]
            if name == "uniform L5":
                uniform5 = top
            pct = f"{100 * top['triangles'] / uniform5['triangles']:.0f}%" if uniform5 else ""
            delta = f"{top['psnr'] - uniform5['psnr']:+.2f}" if uniform5 else ""
            folded = f"{top.get('folded_triangles', 0)} + {top.get('coarse_folded_triangles', 0)}"
            # After the fit (on by default), its own recount and pleats: the
            # level reports' are from before it.
            fitted = d.get("fit_surface", False)
            recount = d["fit_folded_by_nearest_input"] if fitted else top.get("folded_by_nearest_input", "")
            pleats = d["fit_pleats"] if fitted else top.get("pleats", 0)
            if "coarsened_pleats" in d:  # --max-loss: after the coarsening
                recount, pleats = d["coarsened_folded_by_nearest_input"], d["coarsened_pleats"]
            if d.get("untangle", False):  # last, the output's: finest + coarser levels
                recount = f"{d['untangled_folded_by_nearest_input']} + {d['untangled_coarser_folded_by_nearest_input']}"
                pleats = f"{d['untangled_pleats']} + {d['untangled_coarser_pleats']}"
            print(f"| {mesh} | {name} | {d['base_vertices']} | {d['oversampled_vertices']} | {top['vertices']} "
                  f"| {top['triangles']} | {pct} | {top['psnr']:.2f} | {delta} | {folded} "
                  f"| {recount} | {pleats} | {d['wall']:.1f} "
                  f"| {d['rss_mb']:.0f} |", flush=True)


if __name__ == "__main__":
    main()
