#!/usr/bin/env bash
# Builds web/dist and runs the package's tests: Node (the WebAssembly decoder
# against the C++ one, hostile bytes, streaming) and headless Chromium (the
# viewer over a slow server). Needs the native build (tools/setup.sh) for the
# C++ decodes it compares with. Writes screenshots into web/test-output/.
set -euo pipefail
cd "$(dirname "$0")"
bash build.sh
../tools/install_packages.sh chromium
mkdir -p test-output
node --test --test-reporter=spec test/*.test.mjs
