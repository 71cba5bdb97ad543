#!/usr/bin/env bash
# Sets up, builds the libFuzzer targets with clang (ASan + UBSan) into
# build-fuzz/, and runs each for SECONDS (default 30) from its seeds in
# fuzz/corpus/<target>/ and the inputs that once broke it in
# fuzz/regressions/<target>/. Fails if any target crashes, leaks, times out
# or trips a sanitizer; the input that did it is left in
# build-fuzz/artifacts/. New inputs found go to build-fuzz/corpus/, never
# into the committed seeds.
#
#   scripts/fuzz.sh [SECONDS]   fuzz every target
#   scripts/fuzz.sh --seeds     regenerate fuzz/corpus/ with the encoder
#
# FUZZ_BUILD_DIR overrides the build directory.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh

build="${FUZZ_BUILD_DIR:-build-fuzz}"
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -G Ninja \
  -DANIMAT_BUILD_FUZZ=ON -DANIMAT_BUILD_TESTS=OFF -DANIMAT_BUILD_BENCH=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target animat_fuzzers

if [ "${1:-}" = "--seeds" ]; then
  rm -rf fuzz/corpus
  "$build/fuzz/make_corpus" . fuzz/corpus
  echo "fuzz: seeds written to fuzz/corpus/"
  exit 0
fi

seconds="${1:-30}"
targets=(decode_fuzzer work_fuzzer results_fuzzer dispatcher_fuzzer
  scheduler_fuzzer)
mkdir -p "$build/artifacts"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
failed=()
summary=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  log="$build/$target.log"
  mkdir -p "$corpus"
  seeds=("fuzz/corpus/$target")
  if [ -d "fuzz/regressions/$target" ]; then
    seeds+=("fuzz/regressions/$target")
  fi
  echo "fuzz: $target for ${seconds} s"
  if "$build/fuzz/$target" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/artifacts/$target-" \
      "$corpus" "${seeds[@]}" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    summary+=("$target: ${runs:-?} runs, ${rate:-?} exec/s")
  else
    tail -n 40 "$log"
    failed+=("$target")
    summary+=("$target: FAILED (log $log, input in $build/artifacts/)")
  fi
done

printf 'fuzz: %s\n' "${summary[@]}"
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
