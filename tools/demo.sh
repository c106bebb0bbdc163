#!/usr/bin/env bash
# The main job on the bundled sample (data/spot.obj): what the mesh holds,
# then the Draco baseline round trip measured with srcodec's surface metric.
# (Once `srcodec encode`/`decode` land, this script runs them instead.)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
mkdir -p out
set -x
build/tools/srcodec info data/spot.obj
build/tools/srcodec draco data/spot.obj --qp 11 -o out/spot_q11.drc --decoded out/spot_q11.obj
build/tools/srcodec compare data/spot.obj out/spot_q11.obj
