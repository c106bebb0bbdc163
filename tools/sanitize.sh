#!/usr/bin/env bash
# Builds srcodec and its tests with AddressSanitizer and UndefinedBehavior-
# Sanitizer (GCC) in ./build-asan and runs the whole ctest suite there: any
# memory error, leak or undefined behaviour fails the test that hit it.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh --packages-only

san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -O2: at -O1 the CGAL distance queries of the metric ran 10 times slower
# than in the Release build and the rd tests took 4 minutes each; NDEBUG as in the Release
# build, so the code under test is the code we ship. No -Werror: GCC's
# warnings change under instrumentation (false -Wmaybe-uninitialized in
# <regex>, for one), and the normal build already enforces them.
# Configuring again is cheap and picks up changes to these flags.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Sanitize \
  -DCMAKE_CXX_FLAGS_SANITIZE="-O2 -g1 -DNDEBUG $san" \
  -DCMAKE_EXE_LINKER_FLAGS_SANITIZE="$san" \
  -DCMAKE_SHARED_LINKER_FLAGS_SANITIZE="$san" \
  -DSRCODEC_WERROR=OFF >/dev/null

# detect_stack_use_after_return would double the suite's time (fake stacks
# for every frame); run it by hand when hunting such a bug:
#   ASAN_OPTIONS=detect_stack_use_after_return=1 build-asan/tests/NAME_test
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cmake --build build-asan -j"$(nproc)"
cd build-asan
# The package tests build separate projects against this build's libraries
# without the sanitizers' flags; tools/test.sh runs them.
ctest --output-on-failure -j"$(nproc)" --timeout 1200 --label-exclude package
