#!/usr/bin/env bash
# Builds web/dist and runs the package's tests: Node (the WebAssembly decoder
# against the C++ one, hostile bytes, streaming) and headless Chromium (the
# viewer over a slow server). Needs the native build (tools/setup.sh) for the
# C++ decodes it compares with. Writes screenshots into web/test-output/.
set -euo pipefail
cd "$(dirname "$0")"
bash build.sh
if ! dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q "install ok installed"; then
  echo "web/test.sh: installing chromium" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends chromium >/dev/null
fi
mkdir -p test-output
node --test --test-reporter=spec test/*.test.mjs
