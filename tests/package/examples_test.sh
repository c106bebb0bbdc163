#!/usr/bin/env bash
# Installs the build to a temporary prefix, checks what is there, then builds
# examples/ against it as an outside project would (find_package, and
# pkg-config) and runs the examples.
#   usage: examples_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$1"
build="$2"
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT
fail() { echo "examples_test: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in include/srcodec/srcodec.h include/srcodec/status.h include/srcodec/mesh.h include/srcodec/decoder.h \
         include/srcodec/encoder.h lib/libsrcodec_decoder.a bin/srcodec lib/cmake/srcodec/srcodecConfig.cmake \
         lib/cmake/srcodec/srcodecConfigVersion.cmake lib/cmake/srcodec/srcodecTargets.cmake lib/pkgconfig/srcodec.pc; do
  [ -e "$prefix/$f" ] || fail "the install has no $f"
done
encoder=0
[ -e "$prefix/lib/libsrcodec_encoder.a" ] && encoder=1
if grep -rEn '#include <(Eigen|OpenMesh|CGAL|tbb|nanoflann|draco)' "$prefix/include"; then
  fail "a public header includes a dependency's header"
fi

cmake -S "$src/examples" -B "$prefix/examples" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$prefix/examples" -j2 >/dev/null
out="$("$prefix/examples/decode" "$src/tests/data/spot_default.srm")"
echo "$out"
grep -q '^level 2: 1938 vertices' <<<"$out" || fail "decode printed: $out"
grep -q '^level 4: 30978 vertices' <<<"$out" || fail "decode printed: $out"
# The decoder alone: no library of the encoder's or the instruments'.
if ldd "$prefix/examples/decode" | grep -Ei 'openmesh|tbb|cgal|draco|gmp|mpfr'; then
  fail "the decode example links one of the encoder's libraries"
fi

# pkg-config, by hand.
flags="$(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs srcodec)"
g++ -std=c++17 -O2 "$src/examples/decode.cpp" -o "$prefix/decode_pc" $flags
"$prefix/decode_pc" "$src/tests/data/spot_default.srm" | grep -q '^level 2: 1938 vertices' || fail "pkg-config's decode"

if [ "$encoder" = 1 ]; then
  [ -x "$prefix/examples/encode" ] || fail "the encoder is installed but the encode example was not built"
  "$prefix/examples/encode" "$src/data/bunny_npm.obj" "$prefix/bunny.srm" 50
  "$prefix/bin/srcodec" decode "$prefix/bunny.srm" -o "$prefix/bunny.obj" >/dev/null || fail "the encoded file"
fi
echo "examples_test: ok (encoder: $encoder)"
