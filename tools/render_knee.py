#!/usr/bin/python3
"""Renders a mesh's default-rate srcodec file beside Draco's file nearest in bytes: what a viewer
sees at the rate `srcodec encode` picks without a rate option (the knee of its curve).

usage: tools/render_knee.py MESH [--views K,K] [--up X,Y,Z] [--resolution N] [--out DIR] [--name NAME]
                            [--srcodec BIN] [--keep DIR] [-- ENCODE OPTIONS]

Encodes MESH at the default rate (`srcodec encode`, with the options after `--`, e.g. --creases off),
decodes it, encodes it with Draco (-cl 10) at every qp from 6 to 16 and keeps the qp whose file is
nearest the .srm in bytes, measures both decoded meshes against MESH (`srcodec compare --json`),
and renders the three side by side (`srcodec render`) from each view K (one of the visual
measure's 16 directions), one row per view, a caption above each column. Writes OUT/NAME.png and
OUT/NAME.md (the bytes and figures of both files as a Markdown table) and prints the table.
OUT defaults to docs/images, NAME to the mesh's name followed by the encode options
(fandisk-creases-off).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from PIL import Image  # noqa: E402  (Pillow: matplotlib's own image library)

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from rd_corpus import find_srcodec  # noqa: E402

DRACO_QPS = range(6, 17)
RATE_OPTIONS = ("--psnr", "--bytes", "--bpv")  # encode's; without them it keeps the knee
CAPTION_PX = 30  # the band above the panels
ROW_GAP_PX = 6  # between the views' rows
PANEL_GAP_PX = 2  # as `srcodec render` draws them (kPanelGap)


def run(command):
    """Runs a command; its stdout, or exits with its stderr."""
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"render_knee.py: {' '.join(command)} failed:\n{done.stderr.strip()}")
    return done.stdout


def nearest_draco(srcodec, mesh, target_bytes):
    """(qp, bytes) of Draco's file (-cl 10) nearest `target_bytes`, over DRACO_QPS."""
    sizes = {}
    for qp in DRACO_QPS:
        sizes[qp] = json.loads(run([srcodec, "draco", mesh, "--qp", str(qp), "--cl", "10", "--json"]))["bytes"]
    qp = min(DRACO_QPS, key=lambda q: (abs(sizes[q] - target_bytes), q))
    return qp, sizes[qp]


def measured(srcodec, mesh, decoded):
    """PSNR and the visual figures of `decoded` against `mesh`."""
    c = json.loads(run([srcodec, "compare", "--json", mesh, decoded]))
    v = c["visual"]
    return {"psnr": c["psnr"], "normal_deg": v["mean_normal_degrees"], "defect_share": v["defect_share"],
            "depth_psnr": v["depth_psnr"], "turned_over_share": v["turned_over_share"]}


def table(name, encode_options, vertices, rows):
    """The Markdown table of both files: rows are (label, bytes, figures)."""
    options = " ".join(encode_options) if encode_options else "none"
    lines = [f"{name} ({vertices} vertices; encode options: {options})", "",
             "| file | bytes | bits per vertex | PSNR | mean normal angle | visible defects | depth PSNR "
             "| turned over |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for label, size, f in rows:
        lines.append(f"| {label} | {size} | {8 * size / vertices:.2f} | {f['psnr']:.2f} dB | "
                     f"{f['normal_deg']:.2f}° | {100 * f['defect_share']:.2f}% | {f['depth_psnr']:.1f} dB | "
                     f"{100 * f['turned_over_share']:.3f}% |")
    return "\n".join(lines) + "\n"


def compose(view_pngs, captions, resolution, path):
    """Stacks the renders (one a view) under `captions`, one above each panel; writes a grey PNG."""
    rows = [np.asarray(Image.open(p).convert("L")) for p in view_pngs]
    width = rows[0].shape[1]
    height = CAPTION_PX + len(rows) * resolution + (len(rows) - 1) * ROW_GAP_PX
    canvas = np.full((height, width), 255, dtype=np.uint8)
    for i, row in enumerate(rows):
        top = CAPTION_PX + i * (resolution + ROW_GAP_PX)
        canvas[top:top + resolution, :] = row
    dpi = 100
    fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    ax = fig.add_axes([0, 0, 1, 1])
    ax.imshow(canvas, cmap="gray", vmin=0, vmax=255, interpolation="nearest")
    ax.set_axis_off()
    for k, caption in enumerate(captions):
        x = k * (resolution + PANEL_GAP_PX) + resolution / 2
        ax.text(x, CAPTION_PX / 2, caption, ha="center", va="center", fontsize=resolution / 40)
    fig.canvas.draw()
    rgba = np.asarray(fig.canvas.buffer_rgba())
    plt.close(fig)
    Image.fromarray(rgba[:, :, :3].mean(axis=2).round().astype(np.uint8), "L").save(path, optimize=True)


def default_name(mesh, encode_options):
    stem = os.path.splitext(os.path.basename(mesh))[0]
    words = [o.lstrip("-") for o in encode_options]
    return "-".join([stem] + [w for w in words if w])


def parse_args(argv):
    encode_options = []
    if "--" in argv:
        cut = argv.index("--")
        argv, encode_options = argv[:cut], argv[cut + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                usage="tools/render_knee.py MESH [options] [-- ENCODE OPTIONS]")
    p.add_argument("mesh")
    p.add_argument("--views", default="2,9", help="views to render, of the visual measure's 16 (default: 2,9)")
    p.add_argument("--up", help="X,Y,Z shows upwards (srcodec render --up; default: z)")
    p.add_argument("--resolution", type=int, default=512, help="pixels per side of each panel (default: 512)")
    p.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "docs", "images"),
                   help="folder for NAME.png and NAME.md (default: docs/images)")
    p.add_argument("--name", help="output name (default: the mesh's name and the encode options)")
    p.add_argument("--srcodec", help="the srcodec binary (default: build*/tools/srcodec)")
    p.add_argument("--keep", help="keep the encoded, decoded and rendered files in this folder")
    args = p.parse_args(argv)
    try:
        args.views = [int(v) for v in args.views.split(",")]
    except ValueError:
        p.error(f"--views {args.views}: must be view numbers separated by commas")
    args.encode_options = encode_options
    return args


def main():
    args = parse_args(sys.argv[1:])
    mesh = os.path.abspath(args.mesh)
    if not os.path.isfile(mesh):
        sys.exit(f"render_knee.py: {args.mesh}: no such file")
    srcodec = find_srcodec(args.srcodec, "render", "render_knee.py")
    name = args.name or default_name(mesh, args.encode_options)
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        work = args.keep or scratch
        os.makedirs(work, exist_ok=True)
        srm, srm_obj = os.path.join(work, name + ".srm"), os.path.join(work, name + "_srcodec.obj")
        drc_obj = os.path.join(work, name + "_draco.obj")
        print(f"{name}: encoding at the default rate", file=sys.stderr)
        run([srcodec, "encode", "-q", mesh, "-o", srm] + args.encode_options)
        run([srcodec, "decode", srm, "-o", srm_obj])
        srm_bytes = os.path.getsize(srm)
        qp, drc_bytes = nearest_draco(srcodec, mesh, srm_bytes)
        run([srcodec, "draco", mesh, "--qp", str(qp), "--cl", "10", "--decoded", drc_obj])
        vertices = json.loads(run([srcodec, "info", "--json", mesh]))["vertices"]
        srm_fig, drc_fig = measured(srcodec, mesh, srm_obj), measured(srcodec, mesh, drc_obj)

        pngs = []
        for k in args.views:
            pngs.append(os.path.join(work, f"{name}_view{k}.png"))
            run([srcodec, "render", mesh, srm_obj, drc_obj, "-o", pngs[-1], "--view", str(k),
                 "--resolution", str(args.resolution)] + (["--up", args.up] if args.up else []))
        captions = [f"input, {vertices} vertices",
                    f"srcodec, {srm_bytes} bytes, {srm_fig['psnr']:.1f} dB",
                    f"Draco qp {qp}, {drc_bytes} bytes, {drc_fig['psnr']:.1f} dB"]
        picture = os.path.join(args.out, name + ".png")
        compose(pngs, captions, args.resolution, picture)

    rated = any(o.split("=")[0] in RATE_OPTIONS for o in args.encode_options)
    label = " ".join(["srcodec"] + args.encode_options) + ("" if rated else ", default rate")
    rows = [(label, srm_bytes, srm_fig), (f"Draco -cl 10 -qp {qp}", drc_bytes, drc_fig)]
    text = table(name, args.encode_options, vertices, rows)
    with open(os.path.join(args.out, name + ".md"), "w") as f:
        f.write(text)
    print(text, end="")
    print(f"-> {picture} (views {','.join(map(str, args.views))})")


if __name__ == "__main__":
    main()
