#!/usr/bin/env bash
# Regenerates the golden .srm version-1 file and its decoded meshes that
# tests/codec/golden_test.cpp pins. Run only when the format version changes
# (a new version gets new golden files; version 1's stay as they are).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${SRCODEC:-build/tools/srcodec}
"$bin" encode data/spot.obj -o tests/data/golden_v1.srm --levels 2 --base-vertices 100 --bytes 2500 -q
for level in 0 1 2; do
  "$bin" decode tests/data/golden_v1.srm -o tests/data/golden_v1_l$level.obj --level $level
done
