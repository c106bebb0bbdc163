#!/usr/bin/env bash
# Installs what srcodec needs from Debian's packages (only what is missing),
# then configures and builds it in ./build. Safe to run again: the second run
# installs nothing and rebuilds only what changed.
# `tools/setup.sh --packages-only` installs and stops (tools/sanitize.sh and
# tools/fuzz.sh use it: they build in their own folders).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake make g++ pkg-config
  libopenmesh-dev libeigen3-dev libnanoflann-dev
  libdraco-dev draco libcgal-dev libtbb-dev
  libgtest-dev libbenchmark-dev
  python3 python3-numpy python3-scipy python3-matplotlib
  clang libclang-rt-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ "${1:-}" = "--packages-only" ]; then exit 0; fi

build_type="${SRCODEC_BUILD_TYPE:-Release}"
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="$build_type" >/dev/null
fi
cmake --build build -j"$(nproc)"
