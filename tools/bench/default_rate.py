#!/usr/bin/python3
"""The file `srcodec encode MESH -o OUT.srm` writes with no rate option, against Draco at the same PSNR.

For each mesh (default: the whole corpus): `srcodec encode` with no rate
option (the knee of the stream's rate-distortion curve), its bytes, bpv and
PSNR as encode measures them; Draco (`-cl 10`) at quantization bits 6 to 16,
each decoded and measured with `srcodec compare`; Draco's bytes at srcodec's
PSNR, interpolated on its curve (log bytes linear in PSNR between the two
settings around it), and the ratio srcodec / Draco. With OLD=1, also the
file 1 dB below the whole stream's PSNR (`encode --psnr`, the whole stream
measured by `encode --bytes`), the rule the knee is compared with: two more
remeshes per mesh. Prints a
Markdown table.

usage: /usr/bin/python3 tools/bench/default_rate.py [MESH ...]
       OLD=1 /usr/bin/python3 tools/bench/default_rate.py spot.obj
"""
import math
import os
import sys
import tempfile
import time

from srcodec_cli import CORPUS, corpus_meshes, draco_point, or_exit, run_json


def draco_curve(mesh, tmp):
    """(PSNR, bytes) of Draco at quantization bits 6..16, in increasing PSNR."""
    curve = []
    for qp in range(6, 17):
        size, q = draco_point(mesh, qp, os.path.join(tmp, f"draco{qp}.ply"))
        curve.append((q, size))
    return sorted(curve)


def bytes_at(curve, psnr):
    """Draco's bytes at `psnr` on its curve; None outside it."""
    for (p0, b0), (p1, b1) in zip(curve, curve[1:]):
        if p0 <= psnr <= p1 and p1 > p0:
            t = (psnr - p0) / (p1 - p0)
            return math.exp(math.log(b0) + t * (math.log(b1) - math.log(b0)))
    return None


def encode(args):
    """`srcodec encode ARGS --json -q`'s output, with its wall time (rate control included) as "wall"."""
    start = time.monotonic()
    coded = run_json(["encode"] + args + ["--json", "-q"])
    coded["wall"] = time.monotonic() - start
    return coded


def row(name, what, coded, curve):
    draco = bytes_at(curve, coded["psnr"])
    ratio = f"{coded['bytes'] / draco:.2f}" if draco else "outside Draco's curve"
    draco = f"{draco:.0f}" if draco else "-"
    return (f"| {name} | {what} | {coded['bytes']} | {coded['bpv']:.2f} | {coded['psnr']:.2f} | {draco} | {ratio} "
            f"| {coded['wall']:.1f} |")


def main():
    meshes = sys.argv[1:] or corpus_meshes()
    old = os.environ.get("OLD") == "1"
    print("| mesh | srcodec file | bytes | bpv | PSNR dB | Draco bytes at that PSNR | srcodec / Draco "
          "| encode s (wall) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in meshes:
            mesh = name if os.path.exists(name) else os.path.join(CORPUS, name)
            out = os.path.join(tmp, "out.srm")
            curve = draco_curve(mesh, tmp)
            coded = encode([mesh, "-o", out])
            print(row(os.path.basename(mesh), f"default: {coded['rate']}", coded, curve), flush=True)
            if old:
                whole = encode([mesh, "-o", out, "--bytes", "1000000000"])
                coded = encode([mesh, "-o", out, "--psnr", str(whole["psnr"] - 1.0)])
                print(row(os.path.basename(mesh), "1 dB below the whole stream", coded, curve), flush=True)


if __name__ == "__main__":
    or_exit(main)
