# Sourced by scripts/accuracy.sh and scripts/calibration_accuracy.sh: render one simulated
# capture and measure a reconstruction of it. Needs $bin (the sewer3d binary).

# render_scene DIR TRUE_MODULE scene-args...: the capture (pattern.png, texture.png,
# scene.json) at S = 2 with the renderer's realistic noise.
render_scene() {
  local dir=$1 module=$2
  shift 2
  "$bin" simulate frame --module "$module" "$@" --out "$dir" --supersampling 2 >/dev/null
}

# measure_scene DIR SURFACE MODULE TAG: reconstructs DIR's capture with MODULE into
# DIR/TAG, evaluates it against the scene's truth and prints
# "spots points fit_rms fit_max diameter truth_rms truth_max far" (diameter "—" for planes).
measure_scene() {
  local dir=$1 surface=$2 module=$3 tag=$4
  "$bin" reconstruct --module "$module" --image "$dir/pattern.png" --texture "$dir/texture.png" \
    --out "$dir/$tag" >/dev/null
  "$bin" evaluate "$surface" --cloud "$dir/$tag/cloud.ply" --truth "$dir/scene.json" >"$dir/$tag/evaluate.txt"
  local spots points fit truth diameter
  spots=$(grep -o '"spots_found": [0-9]*' "$dir/$tag/report.json" | grep -o '[0-9]*$')
  points=$(grep -o '"points": [0-9]*' "$dir/$tag/report.json" | grep -o '[0-9]*$')
  fit=$(grep '^fit' "$dir/$tag/evaluate.txt" | sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm/\1 \2/')
  diameter=$(grep '^cylinder' "$dir/$tag/evaluate.txt" | sed -E 's/cylinder +diameter ([0-9.]+) mm.*/\1/' || true)
  truth=$(grep 'to the true surface' "$dir/$tag/evaluate.txt" |
    sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm, ([0-9]+) farther.*/\1 \2 \3/')
  echo "$spots $points $fit ${diameter:-—} $truth"
}

# The paper's Tables 1 and 2: name surface scene-args.
ACCURACY_SCENES=(
  "plane_90 plane --scene plane --distance-mm 90"
  "plane_140 plane --scene plane --distance-mm 140"
  "cylinder_200 cylinder --scene cylinder --diameter-mm 200"
  "cylinder_300 cylinder --scene cylinder --diameter-mm 300"
  "cylinder_400 cylinder --scene cylinder --diameter-mm 400"
)
