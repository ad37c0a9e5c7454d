#!/usr/bin/env bash
# Regenerates the accuracy table of docs/accuracy.md: the paper's Table 1 (planes at 90 and
# 140 mm) and Table 2 (cylinders Ø200, Ø300, Ø400) on simulated captures of the default
# module with realistic noise. Usage: scripts/accuracy.sh [OUT_DIR] (after scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=./build/sewer3d
out=${1:-out/accuracy}
mkdir -p "$out"
"$bin" module --out "$out/module" >/dev/null
printf '| capture | spots | points | fit RMS (mm) | fit max (mm) | diameter (mm) | RMS to truth (mm) | max to truth (mm) | points > 1 mm off |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
run() {  # name surface scene-args...
  local name=$1 surface=$2; shift 2
  "$bin" simulate frame --module "$out/module/module.json" "$@" --out "$out/$name" --supersampling 2 >/dev/null
  "$bin" reconstruct --module "$out/module/module.json" --image "$out/$name/pattern.png" \
    --texture "$out/$name/texture.png" --out "$out/$name/reconstruction" >/dev/null
  "$bin" evaluate "$surface" --cloud "$out/$name/reconstruction/cloud.ply" --truth "$out/$name/scene.json" \
    >"$out/$name/evaluate.txt"
  local spots points rms max diameter truth_rms truth_max far
  spots=$(grep -o '"spots_found": [0-9]*' "$out/$name/reconstruction/report.json" | grep -o '[0-9]*$')
  points=$(grep -o '"points": [0-9]*' "$out/$name/reconstruction/report.json" | grep -o '[0-9]*$')
  rms=$(grep '^fit' "$out/$name/evaluate.txt" | sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm/\1/')
  max=$(grep '^fit' "$out/$name/evaluate.txt" | sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm/\2/')
  diameter=$(grep '^cylinder' "$out/$name/evaluate.txt" | sed -E 's/cylinder +diameter ([0-9.]+) mm.*/\1/' || true)
  local truth_line
  truth_line=$(grep 'to the true surface' "$out/$name/evaluate.txt")
  truth_rms=$(sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm, ([0-9]+) farther.*/\1/' <<<"$truth_line")
  truth_max=$(sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm, ([0-9]+) farther.*/\2/' <<<"$truth_line")
  far=$(sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm, ([0-9]+) farther.*/\3/' <<<"$truth_line")
  printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$spots" "$points" "$rms" "$max" \
    "${diameter:-—}" "$truth_rms" "$truth_max" "$far"
}
run plane_90 plane --scene plane --distance-mm 90
run plane_140 plane --scene plane --distance-mm 140
run cylinder_200 cylinder --scene cylinder --diameter-mm 200
run cylinder_300 cylinder --scene cylinder --diameter-mm 300
run cylinder_400 cylinder --scene cylinder --diameter-mm 400
