#!/usr/bin/python3
"""How the default encode's time and memory grow with the input, from 10k to ~10M vertices.

Each mesh is encoded once with the default options (`srcodec encode MESH -o OUT.srm --json`) under
`/usr/bin/time -v`: wall seconds, CPU seconds (user + system), peak resident memory, and from the
encoder's report the oversampled vertex count, the file's bytes and PSNR. With --igea, the series is
rocker-arm, stanford-bunny and igea from the corpus, then igea after one, two and three Loop steps
(made once with `srcodec subdivide` into --cache). Prints a Markdown table, with the growth exponent
of each step (log time ratio over log size ratio: 1 is linear, n log n is a little above 1), writes
the runs as JSON and, with --plot, a log-log plot of time and memory against the input's vertices
with n and n log n drawn through the first point of 100k vertices or more.

usage: /usr/bin/python3 tools/bench/encode_scaling.py [--srcodec BIN] [--json OUT.json] [--plot OUT.png]
                                                      (--igea [--meshes DIR] [--cache DIR] | MESH ...)
       /usr/bin/python3 tools/bench/encode_scaling.py --from-json RUNS.json [--plot OUT.png]
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def igea_series(srcodec, meshes, cache):
    """The corpus meshes of the series and igea after 1, 2, 3 Loop steps (made once into `cache`)."""
    paths = [os.path.join(meshes, m) for m in ("rocker-arm.obj", "stanford-bunny.obj", "igea.ply")]
    os.makedirs(cache, exist_ok=True)
    for steps in (1, 2, 3):
        out = os.path.join(cache, f"igea_loop{steps}.ply")
        if not os.path.exists(out):
            tmp = out + ".part.ply"
            subprocess.run([srcodec, "subdivide", paths[2], "-o", tmp, "--scheme", "loop", "--steps", str(steps)],
                           check=True, stdout=subprocess.DEVNULL)
            os.replace(tmp, out)
        paths.append(out)
    return paths


def time_v(stderr, key):
    match = re.search(re.escape(key) + r": ([\d:.]+)", stderr)
    return match.group(1) if match else None


def encode(srcodec, mesh):
    """One default encode under /usr/bin/time -v: its figures, or its error."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.srm")
        run = subprocess.run(["/usr/bin/time", "-v", srcodec, "encode", mesh, "-o", out, "--json"],
                             capture_output=True, text=True)
        row = {"mesh": os.path.basename(mesh)}
        if run.returncode != 0:
            row["error"] = run.stderr.strip().splitlines()[-25:]
            return row
        report = json.loads(run.stdout)
        wall = time_v(run.stderr, "Elapsed (wall clock) time (h:mm:ss or m:ss)")
        row["wall_s"] = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.split(":"))))
        row["cpu_s"] = float(time_v(run.stderr, "User time (seconds)")) + float(
            time_v(run.stderr, "System time (seconds)"))
        row["peak_mb"] = int(time_v(run.stderr, "Maximum resident set size (kbytes)")) / 1024.0
        row["vertices"] = report["input_vertices"]
        # The remesher's progress line; no line: no oversampling.
        over = re.search(r"^remesh: oversampled .*?: (\d+) vertices", run.stderr, re.M)
        row["oversampled"] = int(over.group(1)) if over else row["vertices"]
        row["bytes"] = report.get("bytes")
        row["psnr"] = report.get("psnr")
        return row


def table(rows):
    lines = ["| input | vertices | oversampled | wall s | CPU s | peak MB | bytes | PSNR dB | growth (wall) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    prev = None
    for r in rows:
        if "error" in r:
            lines.append(f"| {r['mesh']} | failed: {r['error'][-1]} | | | | | | | |")
            continue
        growth = ""
        if prev and r["vertices"] > prev["vertices"]:
            growth = f"{math.log(r['wall_s'] / prev['wall_s']) / math.log(r['vertices'] / prev['vertices']):.2f}"
        psnr = f"{r['psnr']:.2f}" if r.get("psnr") is not None else ""
        lines.append(f"| {r['mesh']} | {r['vertices']} | {r['oversampled']} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} "
                     f"| {r['peak_mb']:.0f} | {r['bytes']} | {psnr} | {growth} |")
        prev = r
    return "\n".join(lines)


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [r for r in rows if "error" not in r]
    n = [r["vertices"] for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, key, label in ((left, "wall_s", "wall seconds"), (right, "peak_mb", "peak memory, MB")):
        y = [r[key] for r in rows]
        ax.loglog(n, y, "o-", label="srcodec encode")
        ref = next((i for i, v in enumerate(n) if v >= 100000), None)
        if ref is not None:
            xs = [v for v in n if v >= n[ref]]
            ax.loglog(xs, [y[ref] * v / n[ref] for v in xs], "--", color="gray", label="n")
            ax.loglog(xs, [y[ref] * v * math.log(v) / (n[ref] * math.log(n[ref])) for v in xs], ":", color="black",
                      label="n log n")
        ax.set_xlabel("input vertices")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("Default encode on the 2-core machine (docs/encoder_speed.md)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("meshes", nargs="*")
    parser.add_argument("--srcodec", default=os.environ.get("SRCODEC", os.path.join(ROOT, "build/tools/srcodec")))
    parser.add_argument("--igea", action="store_true", help="the series from the corpus and igea's Loop steps")
    parser.add_argument("--meshes", dest="mesh_dir", default=os.path.join(ROOT, "..", "shared", "data", "meshes"))
    parser.add_argument("--cache", default=os.path.expanduser("~/.cache/srcodec-bench/meshes"))
    parser.add_argument("--json")
    parser.add_argument("--plot")
    parser.add_argument("--from-json")
    args = parser.parse_args()
    if args.from_json:
        rows = json.load(open(args.from_json))["runs"]
    else:
        paths = igea_series(args.srcodec, args.mesh_dir, args.cache) if args.igea else args.meshes
        if not paths:
            parser.error("give meshes or --igea")
        rows = []
        for path in paths:
            rows.append(encode(args.srcodec, path))
            r = rows[-1]
            print(f"{r['mesh']}: " + (f"failed" if "error" in r else f"{r['wall_s']:.1f} s, {r['peak_mb']:.0f} MB"),
                  file=sys.stderr, flush=True)
        if args.json:
            json.dump({"srcodec": args.srcodec, "runs": rows}, open(args.json, "w"), indent=1)
    print(table(rows))
    if args.plot:
        plot(rows, args.plot)
    return 1 if any("error" in r for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
