#!/usr/bin/env bash
# Quick start, step 2: install dependencies, build, run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc 2>/dev/null || echo 2)"
