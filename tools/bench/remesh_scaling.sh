#!/usr/bin/env bash
# How `srcodec remesh` grows with the input: rocker-arm (10k vertices), igea
# (134k) and igea after two Loop steps (2.1M), at 2 levels without
# oversampling, so every run works on its own input (the default oversampling
# would take the 2.1M-vertex mesh to 8.6M). The base size is one vertex per
# 64 input vertices, at most 4000: the default base size at 2 levels without
# oversampling would ask for more output vertices than half the input, which
# the remesher refuses. Wall time and peak memory from /usr/bin/time; the
# error figures use 20000 samples per surface to keep the measuring out of
# the way. Prints Markdown.
# usage: tools/bench/remesh_scaling.sh [MESH_DIR]   (table in docs/remesh_quality.md)
set -euo pipefail
cd "$(dirname "$0")/../.."
dir="${1:-../shared/data/meshes}"
srcodec=build/tools/srcodec
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$srcodec" subdivide "$dir/igea.ply" -o "$tmp/igea_loop2.ply" --scheme loop --steps 2 >/dev/null
echo "| input | vertices | base | level-2 vertices | PSNR dB | seconds | peak MB |"
echo "|---|---|---|---|---|---|---|"
for mesh in "$dir/rocker-arm.obj" "$dir/igea.ply" "$tmp/igea_loop2.ply"; do
  base=$("$srcodec" info "$mesh" --json | /usr/bin/python3 -c 'import json, sys; print(min(4000, json.load(sys.stdin)["vertices"] // 64))')
  /usr/bin/time -v "$srcodec" remesh "$mesh" -o "$tmp/out.ply" --levels 2 --oversample 0 --base-vertices "$base" \
    --json --quiet --samples 20000 >"$tmp/run.json" 2>"$tmp/time.txt"
  /usr/bin/python3 - "$mesh" "$tmp/run.json" "$tmp/time.txt" <<'PY'
import json, os, re, sys
d = json.load(open(sys.argv[2]))
t = open(sys.argv[3]).read()
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1)) / 1024
wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", t).group(1)
secs = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.split(":"))))
top = d["levels"][-1]
print(f"| {os.path.basename(sys.argv[1])} | {d['input_vertices']} | {d['base_vertices']} "
      f"| {top['vertices']} | {top['psnr']:.2f} | {secs:.1f} | {rss:.0f} |")
PY
done
