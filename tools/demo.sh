#!/usr/bin/env bash
# The main job on the bundled sample (data/spot.obj): encode it into a
# progressive .srm file (remesh, wavelets, embedded coding), look inside,
# decode it level by level and from a prefix of its bytes, measure the result
# against the input, and set it beside Draco's round trip.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
mkdir -p out
set -x
build/tools/srcodec info data/spot.obj
build/tools/srcodec encode data/spot.obj -o out/spot.srm --levels 3
build/tools/srcodec info out/spot.srm
for level in 0 1 2 3; do
  build/tools/srcodec decode out/spot.srm -o "out/spot_l$level.obj" --level "$level"
done
build/tools/srcodec decode out/spot.srm -o out/spot_prefix.obj --bytes 1000
build/tools/srcodec compare data/spot.obj out/spot_l3.obj
build/tools/srcodec compare data/spot.obj out/spot_prefix.obj
# Draco at 8 bits: of its settings, the one nearest the PSNR of this demo's default file.
build/tools/srcodec draco data/spot.obj --qp 8 -o out/spot_q8.drc --decoded out/spot_q8.obj
build/tools/srcodec compare data/spot.obj out/spot_q8.obj
