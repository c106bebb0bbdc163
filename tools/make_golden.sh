#!/usr/bin/env bash
# Regenerates the golden .srm file of one format version and its decoded
# meshes, which tests/codec/golden_test.cpp pins. Run only when a new format
# version comes (it gets new golden files; older versions' stay as they are):
#   tools/make_golden.sh VERSION    (1, 2 or 3; default 2)
# Version 1: no raw planes, cut at 2500 bytes (inside the coded planes).
# Version 2: the default raw planes, cut at 5400 bytes: inside plane 0, so
# that raw segments of every level are decoded and the last one is cut.
# Version 3 (creases): tests/data/creases_v3.srm, which the codec's test
# writes from a sphere built in code with creases on a third of its base
# edges (tests/codec/srm_codec_test.cpp); no meshes are pinned, since they
# follow the wavelet's crease rules.
#   tools/make_golden.sh cube
# writes tests/data/cube_creases_v3.srm: a cube of 10 x 10 squares a face
# encoded with --creases keep at the default rate (its creases are the cube's
# 12 edges and its faces decode flat), for the tests of normals split at
# creases.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${SRCODEC:-build/tools/srcodec}
version="${1:-2}"
if [[ "$version" == cube ]]; then
  dir=$(mktemp -d)
  trap 'rm -rf "$dir"' EXIT
  python3 - "$dir/cube.obj" <<'PY'
import sys
n, index, lines, faces = 10, {}, [], []
def vertex(p):
    if p not in index:
        index[p] = len(index) + 1
        lines.append('v %g %g %g' % p)
    return index[p]
for axis in range(3):
    for s in (-1, 1):
        def at(i, j):  # both faces of an axis facing out
            p = [0, 0, 0]
            p[axis], p[(axis + 1) % 3], p[(axis + 2) % 3] = s, *((i, j) if s > 0 else (j, i))
            return tuple(2 * c / n - 1 if k != axis else c for k, c in enumerate(p))
        for i in range(n):
            for j in range(n):
                a, b, c, d = (vertex(at(*q)) for q in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)))
                faces += ['f %d %d %d' % (a, b, c), 'f %d %d %d' % (a, c, d)]
open(sys.argv[1], 'w').write('\n'.join(lines + faces) + '\n')
PY
  "$bin" encode "$dir/cube.obj" -o tests/data/cube_creases_v3.srm --levels 3 --base-vertices 40 --creases keep -q
  exit
fi
if [[ "$version" == 3 ]]; then
  SRCODEC_WRITE_SAMPLE=1 "$(dirname "$bin")/../tests/srm_codec_test" \
    --gtest_filter=SrmCodecCreases.TheSampleFileHoldsThisEncodersCreases
  exit
fi
case "$version" in
  1) rate=(--bytes 2500 --raw-planes 0) ;;
  2) rate=(--bytes 5400) ;;
  *) echo "make_golden.sh: no golden file for version $version" >&2; exit 2 ;;
esac
out="tests/data/golden_v$version"
"$bin" encode data/spot.obj -o "$out.srm" --levels 2 --base-vertices 100 "${rate[@]}" -q
for level in 0 1 2; do
  "$bin" decode "$out.srm" -o "${out}_l$level.obj" --level $level
done
