#!/usr/bin/python3
"""Runs `srcodec rd` over every mesh of a folder (or the meshes named) and writes
a Markdown report: a summary table, then per mesh its plot and its rd.csv as a
table, and the median Bjøntegaard delta rate of srcodec against Draco.

usage: tools/rd_corpus.py [--meshes DIR] [MESH ...] --out DIR [--srcodec BIN] [--report-only]
                          [rd options: --levels N --base-vertices N --threshold T
                           --uniform --oversample S --scheme S --points N --samples N --cut C]

Options it does not know are passed to `srcodec rd` unchanged. Each mesh gets
OUT/<name>/ (rd.csv, rd.png, summary.json); the report is OUT/report.md.
The whole corpus takes long (each mesh is remeshed once and measured ~21 times).
"""

import argparse
import csv
import glob
import json
import os
import shlex
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
MESH_EXTENSIONS = (".obj", ".off", ".ply", ".stl")


def find_srcodec(explicit, command="rd", script="rd_corpus.py"):
    """The srcodec binary that has `command`: --srcodec, else build*/tools/srcodec."""
    candidates = [explicit] if explicit else (
        [os.path.join(REPO, "build", "tools", "srcodec")] +
        sorted(glob.glob(os.path.join(REPO, "build*", "tools", "srcodec"))))
    for c in candidates:
        if os.access(c, os.X_OK) and subprocess.run([c, command, "--help"], capture_output=True).returncode == 0:
            return c
    sys.exit(f"{script}: no srcodec binary with the `{command}` command among " + ", ".join(candidates) +
             " (build it, or pass --srcodec)")


def list_meshes(folder, named):
    if named:
        return [os.path.abspath(m) for m in named]
    if not os.path.isdir(folder):
        sys.exit(f"rd_corpus.py: {folder} is not a folder")
    return [os.path.join(folder, n) for n in sorted(os.listdir(folder))
            if os.path.splitext(n)[1].lower() in MESH_EXTENSIONS]


def run_rd(srcodec, mesh, out_dir, rd_args, quiet):
    """Runs rd; returns (summary dict or None, error text)."""
    command = [srcodec, "rd", mesh, "-o", out_dir, "--json"] + rd_args + (["-q"] if quiet else [])
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=None if not quiet else subprocess.PIPE, text=True)
    if run.returncode != 0:
        return None, (run.stderr or "").strip() or f"srcodec rd exited with {run.returncode}"
    return json.loads(run.stdout), ""


def pct(x):
    return "n/a" if x is None else f"{100 * x:+.1f}%"


def num(x, digits):
    return "n/a" if x is None else f"{x:.{digits}f}"


def summary_row(name, s):
    if s["bd_rate"] is None:
        bd, lin, shared = "n/a", "n/a", "none"
    else:
        bd, lin = pct(s["bd_rate"]), pct(s["bd_rate_linear"])
        shared = f"{s['bd_psnr_low']:.1f}..{s['bd_psnr_high']:.1f} dB" + (" (narrow)" if s["bd_narrow_overlap"] else "")
    ratios = " / ".join(num(s[f"bytes_ratio_{p}db"], 2) for p in (50, 60, 70))
    cross = ", ".join(f"{c['psnr']:.1f} dB ({c['cheaper_below']} below)" for c in s["crossovers"]) or "none"
    return (f"| {name} | {s['input_vertices']} | {bd} | {lin} | {shared} | {ratios} | {cross} | "
            f"{s['srcodec']['max_psnr']:.1f} dB | {s['encode_time_ratio']:.0f}x | {s['decode_time_ratio']:.1f}x |")


def csv_table(path):
    lines = ["| codec | setting | bytes | bpv | PSNR (dB) | RMS | Hausdorff | normal angle | defect pixels | "
             "turned over | depth PSNR | encode ms | decode ms |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]

    def visual(r, column, form):
        value = float(r.get(column) or "nan")
        return form.format(value) if value == value else "n/a"

    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            lines.append(f"| {r['codec']} | {r['setting']} | {r['bytes']} | {float(r['bpv']):.3f} | "
                         f"{float(r['psnr']):.2f} | {float(r['rms']):.4g} | {float(r['hausdorff']):.4g} | "
                         f"{visual(r, 'normal_deg', '{:.2f} deg')} | "
                         f"{visual(r, 'defect_share', '{:.3%}')} | {visual(r, 'turned_over_share', '{:.4%}')} | "
                         f"{visual(r, 'depth_psnr', '{:.1f} dB')} | "
                         f"{float(r['encode_ms']):.1f} | {float(r['decode_ms']):.1f} |")
    return lines


def seen_table(results):
    """The visual measure at 60 and 70 dB (rd's summary, seen_at): srcodec where its curve reaches
    the PSNR against Draco's curve at the same bytes and at the same PSNR."""
    lines = ["What a viewer sees (`srcodec rd` summary; tools/measure/visual_difference.h): srcodec where its curve "
             "reaches the PSNR against Draco's curve interpolated at the same bytes (n/a where srcodec's file is "
             "smaller than Draco's smallest, 6 bits) and at the same PSNR; each cell srcodec / Draco.", "",
             "| mesh | PSNR | srcodec bytes | normal angle (deg), equal bytes | equal PSNR | defect pixels, equal bytes "
             "| equal PSNR | turned-over area, equal bytes | equal PSNR |",
             "|---|---:|---:|---|---|---|---|---|---|"]

    def pair(a, b, key, form):
        return f"{form.format(a[key])} / {form.format(b[key])}" if a and b else "n/a"

    for name, s, _ in results:
        for e in (s or {}).get("seen_at", []):
            if e["psnr"] < 60:
                continue
            a, b, c = e.get("srcodec"), e.get("draco_same_bytes"), e.get("draco_same_psnr")
            if not a:
                lines.append(f"| {name} | {e['psnr']:.0f} dB | n/a (not reached) | | | | | | |")
                continue
            lines.append(f"| {name} | {e['psnr']:.0f} dB | {a['bytes']:.0f} | "
                         f"{pair(a, b, 'normal_degrees', '{:.2f}')} | {pair(a, c, 'normal_degrees', '{:.2f}')} | "
                         f"{pair(a, b, 'defect_share', '{:.2%}')} | {pair(a, c, 'defect_share', '{:.2%}')} | "
                         f"{pair(a, b, 'turned_over_share', '{:.3%}')} | {pair(a, c, 'turned_over_share', '{:.3%}')} |")
    return lines if len(lines) > 4 else []


def median_line(results):
    bds = [s["bd_rate"] for _, s, _ in results if s and s["bd_rate"] is not None]
    lins = [s["bd_rate_linear"] for _, s, _ in results if s and s["bd_rate"] is not None]
    if not bds:
        return "No mesh has a PSNR range shared by both codecs: no median BD-rate."
    without = [n for n, s, _ in results if s and s["bd_rate"] is None]
    failed = [n for n, s, _ in results if not s]
    text = (f"**Median BD-rate of srcodec against Draco: {pct(statistics.median(bds))}** "
            f"(cubic fit, VCEG-M33; piecewise-linear: {pct(statistics.median(lins))}) over {len(bds)} mesh"
            f"{'es' if len(bds) != 1 else ''}.")
    if without:
        text += " No shared PSNR range (left out): " + ", ".join(without) + "."
    if failed:
        text += " Failed (left out): " + ", ".join(failed) + "."
    return text


def write_report(path, results, invocation, rd_args):
    out = ["# srcodec against Draco: rate-distortion", "",
           f"Made by `{invocation}`; `srcodec rd` options: "
           f"`{' '.join(rd_args) or '(defaults)'}`. Rate: whole-file bytes, bits per vertex of the input mesh "
           "(as read and cleaned); distortion: symmetric surface distance, PSNR = 20 log10(bbox diagonal / RMS). "
           "Draco: `-cl 10`, 6..16 quantization bits. BD-rate < 0: srcodec needs fewer bytes for the same PSNR, "
           "averaged over the PSNR range both codecs cover.", "",
           median_line(results), "",
           "| mesh | vertices | BD-rate | BD-rate (linear) | shared PSNR | bytes srcodec/Draco at 50 / 60 / 70 dB "
           "| crossover | srcodec best | encode time x | decode time x |",
           "|---|---:|---:|---:|---|---|---|---:|---:|---:|"]
    for name, s, error in results:
        out.append(summary_row(name, s) if s else f"| {name} | error: {error.splitlines()[-1] if error else ''} |"
                   + " |" * 8)
    seen = seen_table(results)
    if seen:
        out += [""] + seen
    for name, s, error in results:
        out += ["", f"## {name}", ""]
        if not s:
            out += ["```", error, "```"]
            continue
        folder = os.path.basename(os.path.dirname(s["csv"]))
        if s.get("plot"):
            out += [f"![{name}: PSNR against bits per vertex]({folder}/rd.png)", ""]
        out += csv_table(s["csv"])
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def report_only(args, rd_args):
    results = []
    for mesh in list_meshes(args.meshes, args.mesh):
        name = os.path.basename(mesh)
        path = os.path.join(args.out, os.path.splitext(name)[0], "summary.json")
        if not os.path.exists(path):
            results.append((name, None, f"no {path}"))
            continue
        with open(path) as f:
            results.append((name, json.load(f), ""))
    report = os.path.join(args.out, "report.md")
    argv = [a for a in sys.argv[1:] if a != "--report-only"]
    write_report(report, results, "tools/rd_corpus.py " + " ".join(shlex.quote(a) for a in argv), rd_args)
    print(f"rd_corpus: wrote {report}", file=sys.stderr)
    return 1 if any(not s for _, s, _ in results) else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mesh", nargs="*", help="meshes to run (default: every mesh in --meshes)")
    parser.add_argument("--meshes", default=os.path.join(REPO, "..", "shared", "data", "meshes"),
                        help="folder of meshes (default: ../shared/data/meshes)")
    parser.add_argument("--out", required=True, help="folder for the report and one subfolder per mesh")
    parser.add_argument("--srcodec", help="the srcodec binary (default: build*/tools/srcodec with `rd`)")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress from srcodec rd")
    parser.add_argument("--report-only", action="store_true",
                        help="no rd runs: write the report from the summary.json files already in --out")
    args, rd_args = parser.parse_known_args()
    if args.report_only:
        return report_only(args, rd_args)
    srcodec = find_srcodec(args.srcodec)
    meshes = list_meshes(args.meshes, args.mesh)
    os.makedirs(args.out, exist_ok=True)
    results = []
    for i, mesh in enumerate(meshes):
        name = os.path.basename(mesh)
        print(f"rd_corpus: [{i + 1}/{len(meshes)}] {name}", file=sys.stderr, flush=True)
        summary, error = run_rd(srcodec, mesh, os.path.join(args.out, os.path.splitext(name)[0]), rd_args, args.quiet)
        if error:
            print(f"rd_corpus: {name} failed: {error}", file=sys.stderr)
        results.append((name, summary, error))
    report = os.path.join(args.out, "report.md")
    write_report(report, results, "tools/rd_corpus.py " + " ".join(shlex.quote(a) for a in sys.argv[1:]), rd_args)
    print(f"rd_corpus: wrote {report}", file=sys.stderr)
    return 1 if any(not s for _, s, _ in results) else 0


if __name__ == "__main__":
    sys.exit(main())
