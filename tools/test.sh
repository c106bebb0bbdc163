#!/usr/bin/env bash
# Installs, builds and runs the whole test suite: the C++ tests (ctest), then
# the browser package's (web/test.sh: the WebAssembly decoder in Node and the
# viewer in headless Chromium, against this build's decoder).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
(cd build && ctest --output-on-failure -j"$(nproc)" --timeout 600)
bash web/test.sh
