#!/usr/bin/env bash
# Quick start, step 1: install dependencies, build, run the main job.
# Today the main job writes the default module (module.json + pattern) and describes it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
out=${1:-out/default_module}
./build/sewer3d module --out "$out"
./build/sewer3d describe --module "$out/module.json" >/dev/null
echo "demo: done; see $out/ (module.json, pattern.png, pattern.json, pattern_preview.png)"
