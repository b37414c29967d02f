#!/usr/bin/env bash
# Fuzzes every file reader lutex has (fuzz/, README "Fuzzing"): builds the libFuzzer targets in build-fuzz/
# (clang, -DLUTEX_FUZZERS=ON: coverage, AddressSanitizer, UndefinedBehaviorSanitizer, leak detection), then
# runs each target in turn on a copy of its seed corpus fuzz/corpus/NAME/, so the repository's corpus never
# grows. Fails on any crash, sanitizer report, leak, uncaught exception, input slower than 10 s or run over
# 2 GiB; the input that did it is kept (its path is printed) to become a seed once the reader is fixed.
#
# Usage: bash scripts/fuzz.sh [SECONDS_PER_TARGET]        each target for that long (default 30)
#        bash scripts/fuzz.sh --runs N [TARGET...]          each (or each named) target for N executions
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=$root/build-fuzz

seconds=30
runs=""
targets=()
if [ "${1:-}" = "--runs" ]; then
  runs=${2:?"--runs needs a number of executions"}
  shift 2
  targets=("$@")
elif [ $# -gt 0 ]; then
  seconds=$1
fi
if [ ${#targets[@]} -eq 0 ]; then
  targets=(sparse_model_binary sparse_model_text colmap_array ply lut targets board scene light_rig georeference config)
fi

start=$SECONDS
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DLUTEX_FUZZERS=ON -DLUTEX_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" --target lutex_fuzzers --parallel 2
echo "fuzz build: $((SECONDS - start)) s"

# Each target's files (the readers take paths) go under TMPDIR, here a folder of this run, in memory when the
# machine has /dev/shm: rewriting a file on disk for every input makes ext4 flush it, ten times slower.
scratch=${TMPDIR:-/tmp}
if [ -d /dev/shm ] && [ -w /dev/shm ]; then scratch=/dev/shm; fi
work=$(mktemp -d "$scratch/lutex-fuzz.XXXXXX")
export TMPDIR=$work
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

failed=()
printf '%-22s %12s %10s  %s\n' target executions exec/s result
for target in "${targets[@]}"; do
  binary=$build/fuzz/${target}_fuzzer
  [ -x "$binary" ] || { echo "no fuzz target $target (fuzz/CMakeLists.txt lists them)"; exit 2; }
  mkdir -p "$work/$target/artifacts"
  cp -r "$root/fuzz/corpus/$target" "$work/$target/corpus"
  # Binary formats get room for a few records more than their seeds; text and JSON for a few lines more.
  case $target in
    sparse_model_binary|colmap_array|ply|lut) max_len=65536 ;;
    *) max_len=16384 ;;
  esac
  if [ -n "$runs" ]; then limit=(-runs="$runs"); else limit=(-max_total_time="$seconds"); fi
  status=0
  "$binary" "${limit[@]}" -max_len=$max_len -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 \
    -print_final_stats=1 -artifact_prefix="$work/$target/artifacts/" "$work/$target/corpus" \
    >"$work/$target/log" 2>&1 || status=$?
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$target/log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/$target/log" | tail -1)
  if [ "$status" -eq 0 ]; then
    result=clean
  else
    result="FAILED (exit $status; log $work/$target/log)"
    failed+=("$target")
  fi
  printf '%-22s %12s %10s  %s\n' "$target" "${executions:-?}" "${speed:-?}" "$result"
done
echo "fuzz build and runs: $((SECONDS - start)) s"

if [ ${#failed[@]} -gt 0 ]; then
  for target in "${failed[@]}"; do
    echo "=== $target"
    grep -m1 -A40 -E '^==[0-9]+==|runtime error|deadly signal|uncaught exception|out-of-memory|timeout' \
      "$work/$target/log" || tail -40 "$work/$target/log"
    ls "$work/$target/artifacts"/* 2>/dev/null | sed 's/^/input: /'
  done
  exit 1
fi
rm -rf "$work"
