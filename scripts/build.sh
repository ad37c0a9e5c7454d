#!/usr/bin/env bash
# Configures and builds sewer3d (Release) into build/ (or $SEWER3D_BUILD_DIR). Used by demo.sh
# and test.sh. Uses ccache when the machine has it (not required).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
build_dir=${SEWER3D_BUILD_DIR:-build}
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
cmake --build "$build_dir" --parallel "$jobs"
