#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs them, seeded with
# the samples and every past finding (tests/fuzz/regressions/).
#
#   bash tests/fuzz/run_fuzzers.sh [READER_RUNS] [PIPELINE_SECONDS]
#
# A count of 0 skips that target (two runs side by side on two cores:
# `run_fuzzers.sh 10000000 0 & sleep 120; run_fuzzers.sh 0 3600`).
# Defaults are the figures reported in docs/testing.md: 10^7 executions of the reader and
# an hour of the whole pipeline. CI runs a short smoke run (.ci/run) with FUZZ_SEED=1,
# so that it mutates the same way in every run. Each run is
# limited to 10 s and 2 GB; a crash, a time-out, a memory blow-up or an internal
# error (an exception other than kinema::Error) stops the fuzzer with status 1 and
# leaves the input in build-fuzz/findings/ — copy it to tests/fuzz/regressions/
# once fixed, so the regular test suite replays it.
set -euo pipefail
cd "$(dirname "$0")/../.."
reader_runs=${1:-10000000}
pipeline_seconds=${2:-3600}
if ! command -v clang++ >/dev/null; then
  echo "run_fuzzers.sh: clang++ is needed (apt-get install clang libclang-rt-14-dev)" >&2
  exit 2
fi
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DKINEMA_FUZZ=ON -DKINEMA_BUILD_CLI=OFF -DKINEMA_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target kinema_reader_fuzz kinema_pipeline_fuzz
mkdir -p build-fuzz/findings
export ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=0 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
common=(-timeout=10 -rss_limit_mb=2048 -dict=tests/fuzz/kinema.dict -artifact_prefix=build-fuzz/findings/
        -print_final_stats=1)
if [ -n "${FUZZ_SEED:-}" ]; then common+=(-seed="$FUZZ_SEED"); fi
for target in reader pipeline; do
  corpus=build-fuzz/corpus/$target
  mkdir -p "$corpus"
  cp samples/*.toml tests/fuzz/regressions/* "$corpus"/ 2>/dev/null || true
  # The pipeline runs in fork mode: inputs run in child processes that are replaced as
  # they go, so the hour measures each input's memory, not what ASan and libFuzzer
  # accumulate over 10^5 executions (a single process grew past 1.5 GB in 25 minutes);
  # every crash, time-out and memory blow-up of a child still stops the run.
  if [ "$target" = reader ]; then limit=(-runs="$reader_runs")
  else limit=(-max_total_time="$pipeline_seconds" -fork=1 -ignore_crashes=0 -ignore_timeouts=0 -ignore_ooms=0); fi
  [ "${limit[0]#*=}" != 0 ] || continue
  echo "== $target: ${limit[*]}"
  start=$(date +%s)
  status=0
  ./build-fuzz/tests/fuzz/kinema_${target}_fuzz "${common[@]}" "${limit[@]}" "$corpus" >build-fuzz/$target.log 2>&1 ||
    status=$?
  grep -E "^#[0-9]+.*DONE|ERROR|SUMMARY|stat::" build-fuzz/$target.log || true
  echo "== $target: exit $status after $(( $(date +%s) - start )) s (log: build-fuzz/$target.log)"
  if [ "$status" -ne 0 ]; then
    tail -n 60 build-fuzz/$target.log
    exit 1
  fi
done
