#!/usr/bin/python3
"""The encoder's own PSNR against `srcodec compare`'s on the file the encoder picks.

For each mesh (default: every mesh listed in the corpus's MANIFEST.md) and
each rate (default: the knee, `encode` with no rate option, and `--psnr 60`):
`srcodec encode --json` (its PSNR is measured with the encoder's own metric,
remesh/surface_distance.h over remesh/triangle_tree.h), then `srcodec decode`
of the written file and `srcodec compare` (default samples, CGAL's search) of
the input against it. Prints a Markdown table: mesh, rate, bytes, the
encoder's PSNR, compare's PSNR and the difference; exits 1 when a difference
exceeds 0.3 dB (the issue's bound). A rate out of a mesh's reach is a row
that says so.

usage: /usr/bin/python3 tools/bench/encoder_agreement.py [--jobs N] [--rates knee,60] [MESH ...]
MESH is a path or the name of a corpus mesh. --jobs runs that many meshes at
once (each encode uses every core already: 1 unless cores are idle).
"""
import argparse
import concurrent.futures
import os
import re
import sys
import tempfile

from srcodec_cli import CORPUS, Failed, run_json

BOUND_DB = 0.3


def manifest_meshes():
    """The mesh files listed in the corpus's MANIFEST.md table, smallest file first."""
    with open(os.path.join(CORPUS, "MANIFEST.md"), encoding="utf-8") as f:
        names = re.findall(r"^\| ([^|\s]+\.(?:obj|ply|off|stl)) \|", f.read(), re.MULTILINE)
    names = list(dict.fromkeys(names))  # the sha256 table lists them again
    return sorted(names, key=lambda n: os.path.getsize(os.path.join(CORPUS, n)))


def mesh_path(name):
    return name if os.path.exists(name) else os.path.join(CORPUS, name)


def measure(path, rate, tmp):
    """(bytes, encoder's PSNR, compare's PSNR) of `path` encoded at `rate` ("knee" or a PSNR in dB)."""
    stem = os.path.join(tmp, f"{os.path.basename(path)}.{rate}")
    args = ["encode", path, "-o", stem + ".srm", "--json", "-q"]
    if rate != "knee":
        args += ["--psnr", rate]
    coded = run_json(args)
    run_json(["decode", stem + ".srm", "-o", stem + ".ply", "--json"])
    compared = run_json(["compare", path, stem + ".ply", "--json"])
    return coded["bytes"], coded["psnr"], compared["psnr"]


def rows_of(name, rates):
    """The table rows of one mesh, and whether all its differences are within the bound."""
    rows, ok = [], True
    with tempfile.TemporaryDirectory() as tmp:
        for rate in rates:
            label = "knee" if rate == "knee" else f"--psnr {rate}"
            try:
                size, ours, theirs = measure(mesh_path(name), rate, tmp)
            except Failed as e:
                rows.append(f"| {os.path.basename(name)} | {label} | - | - | - | {e} |")
                continue
            diff = ours - theirs
            ok = ok and abs(diff) <= BOUND_DB
            rows.append(f"| {os.path.basename(name)} | {label} | {size} | {ours:.3f} | {theirs:.3f} | {diff:+.4f} |")
    return rows, ok


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("meshes", nargs="*", help="meshes (default: the corpus's MANIFEST.md)")
    parser.add_argument("--jobs", type=int, default=1, help="meshes measured at once")
    parser.add_argument("--rates", default="knee,60", help="comma-separated: knee and/or PSNR targets in dB")
    a = parser.parse_args()
    meshes = a.meshes or manifest_meshes()
    rates = a.rates.split(",")
    print("| mesh | rate | bytes | encoder PSNR dB | compare PSNR dB | difference dB |")
    print("|---|---|---:|---:|---:|---:|")
    all_ok = True
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for rows, ok in pool.map(lambda m: rows_of(m, rates), meshes):
            print("\n".join(rows), flush=True)
            all_ok = all_ok and ok
    return 0 if all_ok else 1


if __name__ == "__main__":
    sys.exit(main())
