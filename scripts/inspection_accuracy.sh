#!/usr/bin/env bash
# The inspection's accuracy on the scenario with every feature kind (issue 18; docs/inspection.md
# "Observations against the simulator"): simulate docs/scenarios/inspection.json, process it
# (rgbd → register → model → inspect → report) and evaluate the observations and the profile
# against the truth. About 10 min on 2 cores; reruns reuse the run and the finished stages.
# Usage: scripts/inspection_accuracy.sh [OUT] (default out/inspection: OUT/run, OUT/ws).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=./build/sewer3d
out=${1:-out/inspection}
if [ ! -f "$out/run/run.json" ]; then
  "$bin" simulate run --scenario docs/scenarios/inspection.json --out "$out/run" --quiet
fi
"$bin" process "$out/run" --out "$out/ws" --quiet
"$bin" evaluate inspection --run "$out/run" --workspace "$out/ws"
"$bin" report "$out/run" --out "$out/ws" --quiet
