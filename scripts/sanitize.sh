#!/usr/bin/env bash
# The CTest suite under AddressSanitizer + UndefinedBehaviorSanitizer (docs/hardening.md): gcc,
# -O1 with line tables, build dir build-asan (or $SEWER3D_ASAN_BUILD_DIR). Ends with one line
# "sanitize: PASS ..." or "sanitize: FAIL ..." and the matching exit status.
# usage: sanitize.sh [--build-only | --ci]
#   --ci: the job .ci/run runs, sized for CI's time: the unit tests of the modules that meet
#   outside input (core, camera, pattern, posegraph, run, io), the fuzz corpus replays and the
#   bad-input table through the instrumented binary; the _sim tests (the same code on rendered
#   images, minutes each when instrumented) and the benchmarks are left out. Built with clang
#   into build-fuzz ($SEWER3D_FUZZ_BUILD_DIR), where scripts/fuzz.sh finds its targets built.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
build_dir=${SEWER3D_ASAN_BUILD_DIR:-build-asan}
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

mode=${1:-}
compiler=(-DCMAKE_CXX_COMPILER=g++ -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
  -DSEWER3D_SANITIZE=ON)
build_targets=()
test_select=()
if [ "$mode" = "--ci" ]; then
  # One clang build for this job and for scripts/fuzz.sh after it: SEWER3D_FUZZ instruments
  # every library for coverage, ASan and UBSan, so the tests run sanitized and the fuzz targets
  # link against the same objects.
  build_dir=${SEWER3D_FUZZ_BUILD_DIR:-build-fuzz}
  compiler=(-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only"
    -DSEWER3D_FUZZ=ON)
fi
t0=$(date +%s)
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${compiler[@]}" \
  -DSEWER3D_BUILD_TESTS=ON -DSEWER3D_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
if [ "$mode" = "--ci" ]; then
  mapfile -t build_targets < <(cmake --build "$build_dir" --target help |
    sed -n 's/^\([a-z0-9_]*\): .*/\1/p' |
    grep -E '^(test_(core|camera|pattern|posegraph|run|io)_|fuzz_|test_cli_exit_code$)' |
    grep -v -e '_sim$' -e '^test_io_posegraph_benchmarks$')
  build_targets=(--target sewer3d "${build_targets[@]}")
  test_select=(-R '^((core|camera|pattern|posegraph|run|io|fuzz)/|cli/(bad_inputs_[0-9]+of[0-9]+|exit_code)$)'
    -E '^io/posegraph_benchmarks$|_sim$')
fi
if ! cmake --build "$build_dir" --parallel "$jobs" "${build_targets[@]}"; then
  echo "sanitize: FAIL (build)"
  exit 1
fi
t1=$(date +%s)
if [ "$mode" = "--build-only" ]; then
  echo "sanitize: built in $((t1 - t0)) s"
  exit 0
fi

# Leaks are checked too: the system libraries (OpenCV, Ceres, TBB, glog) leave no reports.
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
ctest --test-dir "$build_dir" --output-on-failure --parallel "$jobs" "${test_select[@]}" ||
  status=$?
t2=$(date +%s)
if [ "$status" -eq 0 ]; then
  echo "sanitize: PASS (build $((t1 - t0)) s, tests $((t2 - t1)) s)"
else
  echo "sanitize: FAIL (a test failed or a sanitizer reported; see above)"
fi
exit "$status"
