#!/usr/bin/env bash
# The main job on the bundled sample (data/spot.obj): what the mesh holds,
# the Draco baseline round trip measured with srcodec's surface metric, and
# the adaptive semi-regular remesh (every level written to out/).
# (Once `srcodec encode`/`decode` land, this script runs them instead.)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >/dev/null
mkdir -p out
set -x
build/tools/srcodec info data/spot.obj
build/tools/srcodec draco data/spot.obj --qp 11 -o out/spot_q11.drc --decoded out/spot_q11.obj
build/tools/srcodec compare data/spot.obj out/spot_q11.obj
build/tools/srcodec remesh data/spot.obj -o out/spot_remesh.obj --levels 3 --write-levels out/spot_remesh
