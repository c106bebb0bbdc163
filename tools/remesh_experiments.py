#!/usr/bin/python3
"""The paper's remeshing experiments (Kammoun, Payan, Antonini, Figs. 6-9) on
our corpus: remeshing error against triangle count per level, for uniform
refinement, adaptive refinement at several thresholds (and, ours, at geometric
tolerances), and Butterfly against Loop oversampling (and, ours, linear: splits
at the edges' midpoints, on the input's facets). The paper's runs keep its
positions (`--no-fit-surface`); ours ("+ fit", dashed in the plot) run with the
defaults, which fit the finest level to the input surface. Writes a CSV and a
plot.

usage: /usr/bin/python3 tools/remesh_experiments.py [--quick] [--out docs/remesh_experiments]
  (needs build/tools/remesh_experiment, `srcodec remesh` with the experiments' switches, or the binary
  named by $REMESH_EXPERIMENT; python3-matplotlib; the corpus in
  ../shared/data/meshes)
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REMESH_EXPERIMENT = os.environ.get("REMESH_EXPERIMENT", os.path.join(ROOT, "build", "tools", "remesh_experiment"))
CORPUS = os.path.join(ROOT, "..", "shared", "data", "meshes")

# (mesh, levels, extra options) runs; thresholds are in vertices of the
# oversampled input per Voronoi cell (Eq. 5).
# The paper's meshes are 10k-35k-vertex scans; these are the corpus meshes of
# that size that run in minutes on two cores (CAD, genus 1, a cartoon).
FULL = {
    "meshes": ["fandisk.obj", "rocker-arm.obj", "spot.obj"],
    "levels": 4,
    "thresholds": [4, 8, 16],
    # Our geometric criterion (--uniform --tolerance DB), beside the paper's.
    "tolerances": [60, 70],
    "scheme_meshes": ["bunny_npm.obj", "spot.obj"],
}
QUICK = {"meshes": ["armadillo.obj"], "levels": 4, "thresholds": [4], "tolerances": [60],
         "scheme_meshes": ["bunny_npm.obj"]}

FIELDS = ["mesh", "config", "scheme", "oversample", "threshold", "tolerance_db", "fit", "level", "vertices",
          "triangles", "rms", "psnr", "seconds"]
# The paper's runs (uniform, Eq. 5, the oversampling schemes) keep its
# positions: sites on input vertices, no fit to the input surface.
PAPER = ["--no-fit-surface"]


def run(mesh, levels, extra):
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [REMESH_EXPERIMENT, "remesh", os.path.join(CORPUS, mesh), "-o", os.path.join(tmp, "out.obj"), "--levels",
               str(levels), "--json", "--quiet"] + extra
        print(" ".join(cmd[1:]), file=sys.stderr, flush=True)
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def rows_of(mesh, config, scheme, result):
    for lv in result["levels"]:
        yield {"mesh": mesh, "config": config, "scheme": scheme, "oversample": result["oversample_steps"],
               "threshold": "" if result["uniform"] else result["threshold"],
               "tolerance_db": result.get("tolerance_db") or "", "fit": int(result.get("fit_surface", False)),
               "level": lv["level"],
               "vertices": lv["vertices"], "triangles": lv["triangles"], "rms": lv["rms"], "psnr": lv["psnr"],
               "seconds": lv["seconds"]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="one small mesh, for a smoke test")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "remesh_experiments"))
    args = ap.parse_args()
    plan = QUICK if args.quick else FULL
    rows = []
    for mesh in plan["meshes"]:
        rows += rows_of(mesh, "uniform", "butterfly", run(mesh, plan["levels"], ["--uniform"] + PAPER))
        for eps in plan["thresholds"]:
            rows += rows_of(mesh, f"eps={eps}", "butterfly",
                            run(mesh, plan["levels"], ["--threshold", str(eps)] + PAPER))
        # Ours, with the defaults (the fit on): uniform, and the geometric
        # criterion.
        rows += rows_of(mesh, "uniform + fit", "butterfly", run(mesh, plan["levels"], ["--uniform"]))
        for tol in plan["tolerances"]:
            rows += rows_of(mesh, f"tol={tol} dB + fit", "butterfly",
                            run(mesh, plan["levels"], ["--uniform", "--tolerance", str(tol)]))
    # Fig. 6: the input oversampled three times with Butterfly or with Loop
    # (and linearly, ours).
    for mesh in plan["scheme_meshes"]:
        for scheme in ["butterfly", "loop", "linear"]:
            for fit in (False, True):
                rows += rows_of(mesh, f"{scheme} x3" + (" + fit" if fit else ""), scheme,
                                run(mesh, plan["levels"],
                                    ["--uniform", "--oversample", "3", "--scheme", scheme] + ([] if fit else PAPER)))
    with open(args.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    plot(rows, args.out + ".png")
    print(f"wrote {args.out}.csv and {args.out}.png", file=sys.stderr)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    def scheme_run(r):
        return " x3" in r["config"]

    meshes = list(dict.fromkeys((r["mesh"], scheme_run(r)) for r in rows))
    cols = min(3, len(meshes))
    nrows = (len(meshes) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(5 * cols, 4 * nrows), squeeze=False)
    for ax, (mesh, scheme_fig) in zip(axes.flat, meshes):
        sel = [r for r in rows if r["mesh"] == mesh and scheme_run(r) == scheme_fig]
        for config in dict.fromkeys(r["config"] for r in sel):
            pts = [r for r in sel if r["config"] == config]
            fitted = pts[0]["fit"]  # ours: dashed
            ax.plot([r["triangles"] for r in pts], [r["rms"] for r in pts], "o--" if fitted else "o-", label=config)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles")
        ax.set_ylabel("RMS error (vs input)")
        ax.set_title(mesh + (" (oversampling schemes)" if scheme_fig else ""))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    for ax in list(axes.flat)[len(meshes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
