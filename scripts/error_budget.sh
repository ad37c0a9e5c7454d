#!/usr/bin/env bash
# Regenerates the error-budget table of docs/accuracy.md ("Realism"): the fit RMS of the
# paper's five test captures with each error source of the `paper` realism profile alone,
# then all together (docs/simulator.md, "Error sources"). Same captures as
# scripts/accuracy.sh (default module, S = 2, the renderer's realistic noise).
# Usage: scripts/error_budget.sh [OUT_DIR] (after scripts/build.sh; about 15 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/accuracy_lib.sh
bin=./build/sewer3d
out=${1:-out/error_budget}
mkdir -p "$out"
"$bin" module --out "$out/module" >/dev/null
module=$(realpath "$out/module/module.json")
# label|render members added to the realistic renderer's (the paper profile's levels)
configs=(
  "none (realistic renderer)|"
  "spot placement 0.65 px|\"spot_placement_sigma_px\": 0.65"
  "spot power 10 %|\"spot_gain_sigma\": 0.1"
  "speckle contrast 0.1|\"speckle_contrast\": 0.1"
  "lens residual 1e-4|\"lens_residual\": 1e-4"
  "wall relief 0.055 mm|\"relief_mm\": 0.055"
  "subsurface scattering 0.02 mm|\"subsurface_mm\": 0.02"
  "calibration error|\"calibration_focal_px\": 0.3, \"calibration_centre_px\": 0.5, \"calibration_baseline_mm\": 0.015, \"calibration_rotation_deg\": 0.015"
  "all (realism paper)|\"realism\": \"paper\""
)
header='| error source |' rule='|---|'
for scene in "${ACCURACY_SCENES[@]}"; do
  read -r name _ <<<"$scene"
  header+=" $name |" rule+='---|'
done
printf '%s\n%s\n' "$header" "$rule"
for k in "${!configs[@]}"; do
  IFS='|' read -r label members <<<"${configs[$k]}"
  row="| $label |"
  for scene in "${ACCURACY_SCENES[@]}"; do
    read -r name surface args <<<"$scene"
    dir="$out/$k/$name"
    # The scene as scripts/accuracy.sh renders it, with the error sources added to its render
    # members.
    # shellcheck disable=SC2086
    "$bin" simulate frame --module "$module" $args --out "$dir.base" --supersampling 2 >/dev/null
    python3 - "$dir.base/scene.json" "$dir.json" "{$members}" "$module" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
added = json.loads(sys.argv[3])
if "realism" in added:  # the profile's own levels, not the base scene's zeros
    for key in ("spot_placement_sigma_px", "spot_gain_sigma", "speckle_contrast",
                "lens_residual", "relief_mm", "relief_plastic_mm", "subsurface_mm",
                "subsurface_plastic_mm",
                "calibration_focal_px", "calibration_centre_px", "calibration_baseline_mm",
                "calibration_rotation_deg"):
        scene["render"].pop(key, None)
scene["render"].update(added)
scene["module"] = sys.argv[4]
json.dump(scene, open(sys.argv[2], "w"), indent=2)
PY
    "$bin" simulate frame --module "$module" --scene "$dir.json" --out "$dir" >/dev/null
    read -r _ _ rms _ _ _ _ far <<<"$(measure_scene "$dir" "$surface" "$module" reconstruction)"
    row+=" $rms${far:+ ($far > 1 mm)} |"
  done
  printf '%s\n' "$row"
done
