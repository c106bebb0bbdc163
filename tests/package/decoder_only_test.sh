#!/usr/bin/env bash
# The decoder builds alone: configures a clean build with the encoder off,
# fails if the configuration found (or even looked for) any of the encoder's
# or the instruments' libraries, builds the decode-only srcodec and checks
# that it decodes as the full build's does.
#   usage: decoder_only_test.sh SOURCE_DIR FULL_SRCODEC
set -euo pipefail
src="$1"
full="$2"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
fail() { echo "decoder_only_test: $*" >&2; exit 1; }

cmake -S "$src" -B "$dir/build" -DSRCODEC_ENCODER=OFF -DSRCODEC_BUILD_TESTS=OFF >/dev/null
if grep -Ein 'openmesh|cgal|tbb|draco|nanoflann|cli11|benchmark_dir' "$dir/build/CMakeCache.txt"; then
  fail "the decoder-only configuration mentions a library the decoder must not need"
fi
cmake --build "$dir/build" -j2 --target srcodec >/dev/null
dec="$dir/build/tools/srcodec"
if ldd "$dec" | grep -Ei 'openmesh|tbb|cgal|draco'; then fail "the decode-only srcodec links one of them"; fi

sample="$src/tests/data/spot_default.srm"
for args in "" "--level 2" "--bytes 900"; do
  "$dec" decode "$sample" -o "$dir/dec.obj" $args >/dev/null
  "$full" decode "$sample" -o "$dir/full.obj" $args >/dev/null
  cmp -s "$dir/dec.obj" "$dir/full.obj" || fail "decode $args differs from the full build's"
done
"$dec" info "$sample" >/dev/null || fail "info"
if "$dec" encode "$src/data/spot.obj" -o "$dir/x.srm" >/dev/null 2>&1; then fail "encode in a decoder-only build"; fi
echo "decoder_only_test: ok"
