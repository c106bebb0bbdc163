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
  libdraco-dev draco libcgal-dev libembree-dev libtbb-dev libpng-dev
  libgtest-dev libbenchmark-dev
  python3 python3-numpy python3-scipy python3-matplotlib
  clang libclang-rt-14-dev
)
tools/install_packages.sh "${packages[@]}"

if [ "${1:-}" = "--packages-only" ]; then exit 0; fi

build_type="${SRCODEC_BUILD_TYPE:-Release}"
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="$build_type" >/dev/null
fi
cmake --build build -j"$(nproc)"
