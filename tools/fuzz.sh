#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang, ASan and UBSan in
# ./build-fuzz and runs each for SECONDS (default 60). Exits non-zero on any
# finding: the input that triggered it is kept in build-fuzz/findings/.
# The corpus grows in build-fuzz/corpus/ from run to run (seeds:
# fuzz/make_seeds.py); a longer run: bash tools/fuzz.sh 3600
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
tools/setup.sh --packages-only

# The targets read only what the decoder reads, so the encoder stays off.
# -O1 with line tables, as OSS-Fuzz builds; asserts stay on: fuzzing is
# where the programmer's invariants should be checked. No -Werror: the
# warning flags are tuned for GCC, which the normal build enforces.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DSRCODEC_FUZZ=ON -DSRCODEC_ENCODER=OFF -DSRCODEC_BUILD_TESTS=OFF -DSRCODEC_WERROR=OFF >/dev/null
targets=(srm_decode mesh_read)
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/%/_fuzzer}"

python3 fuzz/make_seeds.py . build-fuzz/seeds
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
declare -A max_len=([srm_decode]=16384 [mesh_read]=65536)
failed=()
for t in "${targets[@]}"; do
  rm -rf "build-fuzz/findings/$t"
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/findings/$t"
  echo "fuzz: $t for ${seconds}s" >&2
  # New inputs go to the first folder (corpus); the seeds are read only.
  if ! "build-fuzz/fuzz/${t}_fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
      -max_len="${max_len[$t]}" -print_final_stats=1 -dict="fuzz/$t.dict" \
      -artifact_prefix="build-fuzz/findings/$t/" \
      "build-fuzz/corpus/$t" "build-fuzz/seeds/$t" >"build-fuzz/$t.log" 2>&1; then
    failed+=("$t")
    echo "fuzz: $t found a problem; the end of build-fuzz/$t.log:" >&2
    grep -v '^#[0-9]' "build-fuzz/$t.log" | tail -n 60 >&2
  else
    grep -E '^(Done|stat::number_of_executed_units|stat::peak_rss_mb)' "build-fuzz/$t.log" | tr '\n' ' ' >&2
    echo >&2
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]}; inputs in build-fuzz/findings/ (rerun one: build-fuzz/fuzz/NAME_fuzzer FILE)" >&2
  exit 1
fi
echo "fuzz: no findings" >&2
