#!/usr/bin/env bash
# Checks `srcodec compare` against an independent Metro-style measurement
# (tools/metro_check.py: open3d's raycasting scene, its own sampling) on real
# meshes against their Draco-decoded copies, and prints a Markdown table.
# Needs python3-open3d (apt-get install python3-open3d); not part of setup.
# usage: tools/metric_agreement.sh [MESH_DIR] > docs/metric_agreement.md
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-../shared/data/meshes}"
srcodec=build/tools/srcodec
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "# \`srcodec compare\` against an independent measurement"
echo
echo "Made by \`tools/metric_agreement.sh\`: each mesh against its Draco-decoded copy (-cl 10), 200000 samples per surface,"
echo "srcodec (CGAL AABB tree) against tools/metro_check.py (open3d RaycastingScene, numpy sampling)."
echo
echo "| mesh | Draco qp | srcodec rms | independent rms | difference | srcodec PSNR dB | independent PSNR dB |"
echo "|---|---|---|---|---|---|---|"
for m in bunny_npm armadillo fandisk rocker-arm; do
  for q in 8 10 12; do
    "$srcodec" draco "$dir/$m.obj" --qp "$q" --decoded "$tmp/d.obj" >/dev/null
    a=$("$srcodec" compare --json "$dir/$m.obj" "$tmp/d.obj")
    b=$(/usr/bin/python3 tools/metro_check.py --json "$dir/$m.obj" "$tmp/d.obj" 2>/dev/null)
    /usr/bin/python3 - "$a" "$b" "$m" "$q" <<'PY'
import json, sys
a, b = json.loads(sys.argv[1]), json.loads(sys.argv[2])
print(f"| {sys.argv[3]} | {sys.argv[4]} | {a['rms']:.6g} | {b['rms']:.6g} | {100 * (a['rms'] / b['rms'] - 1):+.2f}% "
      f"| {a['psnr']:.2f} | {b['psnr']:.2f} |")
PY
  done
done
