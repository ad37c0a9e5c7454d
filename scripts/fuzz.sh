#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang, ASan + UBSan, build dir build-fuzz or
# $SEWER3D_FUZZ_BUILD_DIR) and runs each for SECONDS (default 60), starting from its committed
# corpus tests/data/fuzz/<target>/ (docs/hardening.md). New inputs go to BUILD/corpus/<target>,
# findings to BUILD/findings/. Ends with one line per target (executions, result) and
# "fuzz: PASS" or "fuzz: FAIL". With SEWER3D_FUZZ_RUNS=N each target stops after N executions
# instead (SECONDS is then only a cap): the long run is SEWER3D_FUZZ_RUNS=10000000 fuzz.sh 36000.
# One input running SEWER3D_FUZZ_TIMEOUT seconds (default 10, wall clock) is a hang: raise it
# when the fuzzer shares its cores with other work (reniced, it can wait seconds for a core).
# usage: fuzz.sh [SECONDS_PER_TARGET] [TARGET...]   (0 seconds: build only)   targets: module_json scenario_json g2o ply
#                                                   run_index png
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(module_json scenario_json g2o ply run_index png); fi
build_dir=${SEWER3D_FUZZ_BUILD_DIR:-build-fuzz}
jobs=$(nproc 2>/dev/null || echo 2)
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

t0=$(date +%s)
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DSEWER3D_FUZZ=ON -DSEWER3D_BUILD_TESTS=OFF -DSEWER3D_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
if ! cmake --build "$build_dir" --parallel "$jobs" --target "${targets[@]/#/fuzz_}"; then
  echo "fuzz: FAIL (build)"
  exit 1
fi
echo "fuzz: built ${#targets[@]} targets in $(($(date +%s) - t0)) s"
[ "$seconds" -gt 0 ] || exit 0

export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
mkdir -p "$build_dir/findings" "$build_dir/logs"
runs_limit=()
if [ -n "${SEWER3D_FUZZ_RUNS:-}" ]; then runs_limit=(-runs="$SEWER3D_FUZZ_RUNS"); fi
summary=()
failed=0
for t in "${targets[@]}"; do
  mkdir -p "$build_dir/corpus/$t"
  log=$build_dir/logs/$t.log
  status=0
  start=$(date +%s)
  # -timeout: one input taking that long is a hang; -rss_limit_mb: 2 GB is a memory blow-up (one
  # malloc above it is reported too).
  "$build_dir/fuzz/fuzz_$t" "$build_dir/corpus/$t" "tests/data/fuzz/$t" -dict="fuzz/$t.dict" \
    -max_total_time="$seconds" -timeout="${SEWER3D_FUZZ_TIMEOUT:-10}" -rss_limit_mb=2048 -print_final_stats=1 \
    "${runs_limit[@]}" -artifact_prefix="$build_dir/findings/$t-" >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  # Stopped by a finding: no final stats, the last progress line's count instead.
  [ -n "$runs" ] || runs=$(grep -oE '^#[0-9]+' "$log" | tail -1 | tr -d '#')
  took=$(($(date +%s) - start))
  if [ "$status" -eq 0 ]; then
    summary+=("fuzz: $t: ${runs:-?} executions in ${took} s, no finding")
  else
    failed=1
    summary+=("fuzz: $t: FINDING after ${runs:-?} executions (exit $status), see $log")
    grep -m 5 -E "ERROR|SUMMARY|terminate|deadly|timeout|out-of-memory" "$log" || true
  fi
done
printf '%s\n' "${summary[@]}"
if [ "$failed" -eq 0 ]; then
  echo "fuzz: PASS"
else
  echo "fuzz: FAIL (inputs in $build_dir/findings/)"
fi
exit "$failed"
