#!/usr/bin/env bash
# Regenerates the accuracy table of docs/accuracy.md: the paper's Table 1 (planes at 90 and
# 140 mm) and Table 2 (cylinders Ø200, Ø300, Ø400) on simulated captures of the default
# module with realistic noise. Usage: scripts/accuracy.sh [OUT_DIR] (after scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/accuracy_lib.sh
bin=./build/sewer3d
out=${1:-out/accuracy}
mkdir -p "$out"
"$bin" module --out "$out/module" >/dev/null
printf '| capture | spots | points | fit RMS (mm) | fit max (mm) | diameter (mm) | RMS to truth (mm) | max to truth (mm) | points > 1 mm off |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
for scene in "${ACCURACY_SCENES[@]}"; do
  read -r name surface args <<<"$scene"
  # shellcheck disable=SC2086
  render_scene "$out/$name" "$out/module/module.json" $args
  read -r spots points rms max diameter truth_rms truth_max far \
    <<<"$(measure_scene "$out/$name" "$surface" "$out/module/module.json" reconstruction)"
  printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$spots" "$points" "$rms" "$max" \
    "$diameter" "$truth_rms" "$truth_max" "$far"
done
