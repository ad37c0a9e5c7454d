#!/usr/bin/env bash
# End-to-end calibration check (issue 5; docs/calibration.md): simulate checkerboard captures
# of the default module, calibrate the module from them, print the recovered-vs-true table,
# then reconstruct the accuracy scenes (scripts/accuracy.sh) once with the true and once with
# the calibrated module. Usage (after scripts/build.sh):
#   scripts/calibration_accuracy.sh [OUT_DIR] [CAMERA_SIZE WxH, default 2592x1944] [REALISM]
# REALISM (ideal or paper, default ideal) is the captures' (`simulate calibration --realism`).
# Full size takes about half an hour on 2 cores (rendering the captures; an existing
# OUT_DIR/captures is reused).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/accuracy_lib.sh
bin=./build/sewer3d
out=${1:-out/calibration_accuracy}
size=${2:-2592x1944}
realism=${3:-ideal}
mkdir -p "$out"
"$bin" module --out "$out/true" --camera-size "$size" >/dev/null
if [[ ! -f "$out/captures/truth/poses.json" ]]; then
  "$bin" simulate calibration --module "$out/true/module.json" --poses 20 --out "$out/captures" --supersampling 2 \
    --realism "$realism" >/dev/null
fi
"$bin" calibrate module --captures "$out/captures" --board 9x6 --square-mm 10 \
  --out "$out/calibrated/module.json" >"$out/calibrate.txt" 2>"$out/calibrate.err"
grep -v '^  pose' "$out/calibrate.txt"
echo
python3 scripts/compare_modules.py "$out/true/module.json" "$out/calibrated/module.json"
echo
# Each parameter in its standard deviations, against the true module and against the nearest
# module the file can hold for the captures' lenses (docs/calibration.md).
"$bin" evaluate calibration --captures "$out/captures" --module "$out/calibrated/module.json" \
  --out "$out/calibration_evaluation.json"
echo
printf '| capture | fit RMS, true module (mm) | fit RMS, calibrated (mm) | change | RMS to truth, true (mm) | RMS to truth, calibrated (mm) | diameter, true / calibrated (mm) |\n'
printf '|---|---|---|---|---|---|---|\n'
for scene in "${ACCURACY_SCENES[@]}"; do
  read -r name surface args <<<"$scene"
  # shellcheck disable=SC2086
  render_scene "$out/$name" "$out/true/module.json" $args
  read -r _ _ rms_t _ dia_t truth_t _ _ <<<"$(measure_scene "$out/$name" "$surface" "$out/true/module.json" true)"
  read -r _ _ rms_c _ dia_c truth_c _ _ <<<"$(measure_scene "$out/$name" "$surface" "$out/calibrated/module.json" calibrated)"
  change=$(python3 -c "print(f'{100 * ($rms_c - $rms_t) / $rms_t:+.1f} %')")
  printf '| %s | %s | %s | %s | %s | %s | %s / %s |\n' "$name" "$rms_t" "$rms_c" "$change" "$truth_t" "$truth_c" "$dia_t" "$dia_c"
done
