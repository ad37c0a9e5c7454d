#!/usr/bin/env bash
# The CTest suite under AddressSanitizer + UndefinedBehaviorSanitizer (docs/hardening.md): gcc,
# -O1 with line tables, build dir build-asan (or $SEWER3D_ASAN_BUILD_DIR). Ends with one line
# "sanitize: PASS ..." or "sanitize: FAIL ..." and the matching exit status.
# usage: sanitize.sh [--build-only]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
build_dir=${SEWER3D_ASAN_BUILD_DIR:-build-asan}
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

t0=$(date +%s)
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSEWER3D_SANITIZE=ON \
  -DSEWER3D_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
if ! cmake --build "$build_dir" --parallel "$jobs"; then
  echo "sanitize: FAIL (build)"
  exit 1
fi
t1=$(date +%s)
if [ "${1:-}" = "--build-only" ]; then
  echo "sanitize: built in $((t1 - t0)) s"
  exit 0
fi

# Leaks are checked too: the system libraries (OpenCV, Ceres, TBB, glog) leave no reports.
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
ctest --test-dir "$build_dir" --output-on-failure --parallel "$jobs" || status=$?
t2=$(date +%s)
if [ "$status" -eq 0 ]; then
  echo "sanitize: PASS (build $((t1 - t0)) s, tests $((t2 - t1)) s)"
else
  echo "sanitize: FAIL (a test failed or a sanitizer reported; see above)"
fi
exit "$status"
