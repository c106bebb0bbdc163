#!/usr/bin/env bash
# Builds srcodec's JavaScript package into web/dist/: the C++ decoder
# compiled to WebAssembly by Debian's emscripten, the ES modules and their
# TypeScript declarations. Installs what it needs (emscripten, Node.js's npm
# packages of package-lock.json) when missing; safe to run again.
set -euo pipefail
cd "$(dirname "$0")"

packages=(cmake make emscripten libeigen3-dev)
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)
../tools/install_packages.sh "${packages[@]}"

# Debian's emscripten runs its JavaScript optimizer with the system's Node.js,
# which finds Debian's acorn only here.
export NODE_PATH=/usr/share/nodejs
if [ ! -f build-wasm/CMakeCache.txt ]; then
  emcmake cmake -S .. -B build-wasm -DCMAKE_BUILD_TYPE=Release -DSRCODEC_ENCODER=OFF -DSRCODEC_BUILD_TESTS=OFF \
    -DEigen3_DIR=/usr/share/eigen3/cmake >/dev/null
fi
cmake --build build-wasm --target srcodec_wasm -j"$(nproc)"

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules ]; then
  npm ci --no-audit --no-fund
fi

# Into a fresh folder, then moved into place: a failed build leaves the old dist/.
rm -rf dist.new
mkdir dist.new
cp src/*.js src/*.d.ts build-wasm/web/srcodec_decoder.wasm dist.new/
rm -rf dist
mv dist.new dist
echo "web/build.sh: built web/dist ($(du -k dist/srcodec_decoder.wasm | cut -f1) kB of WebAssembly)" >&2
