#!/usr/bin/env bash
# Command-line contract: --help everywhere, one-line errors with non-zero exit, outputs written.
set -u
bin=${SEWER3D:?set SEWER3D to the sewer3d binary}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_ok CMD...: exit 0
expect_ok() { "$@" >"$tmp/out" 2>"$tmp/err" || fail "exit $? from: $* ($(head -c 300 "$tmp/err"))"; }
# expect_error NEEDLE CMD...: non-zero exit (left in $rc), exactly one stderr line containing NEEDLE
expect_error() {
  local needle=$1; shift
  if "$@" >"$tmp/out" 2>"$tmp/err"; then rc=0; fail "exit 0 from: $*"; return; else rc=$?; fi
  local lines; lines=$(wc -l <"$tmp/err")
  [ "$lines" -eq 1 ] || fail "expected one stderr line from: $* (got $lines: $(cat "$tmp/err"))"
  grep -q -- "$needle" "$tmp/err" || fail "stderr of '$*' lacks '$needle': $(cat "$tmp/err")"
}

# expect_file_error FILE FIELD CMD...: exit 3 (bad file) with one stderr line naming the file
# and the field in the file's own terms, and nothing of the code's internals.
expect_file_error() {
  local file=$1 field=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ "$rc" -eq 3 ] || fail "exit $rc, not 3, from: $* ($(cat "$tmp/err"))"
  local lines; lines=$(wc -l <"$tmp/err")
  [ "$lines" -eq 1 ] || fail "expected one stderr line from: $* (got $lines: $(cat "$tmp/err"))"
  grep -qF -- "$file: $field" "$tmp/err" || fail "stderr of '$*' does not name '$file: $field': $(cat "$tmp/err")"
  if grep -q "check failed\|\.cpp:" "$tmp/err"; then fail "stderr of '$*' shows internals: $(cat "$tmp/err")"; fi
}

expect_ok "$bin" --help
for sub in module pattern describe posegraph simulate reconstruct evaluate; do
  grep -q "$sub" "$tmp/out" || fail "--help does not list $sub"
done
for sub in module pattern describe posegraph; do
  expect_ok "$bin" "$sub" --help
  grep -q -- "--" "$tmp/out" || fail "$sub --help shows no options"
done

expect_error "error" "$bin"
expect_error "error" "$bin" no-such-command
expect_error "--bogus" "$bin" module --out "$tmp/m" --bogus
expect_error "--out" "$bin" module
expect_error "WxH" "$bin" module --out "$tmp/m" --camera-size 640by480
expect_error "--cols" "$bin" pattern --out "$tmp/p.png" --cols -5
expect_error "--window" "$bin" pattern --out "$tmp/p.png" --window 12
expect_error "no_such.json" "$bin" describe --module "$tmp/no_such.json"
printf '{"camera": 3}' >"$tmp/bad.json"
expect_error "camera" "$bin" describe --module "$tmp/bad.json"
expect_error "not reached" "$bin" pattern --out "$tmp/never.png" --rows 3 --cols 8 \
  --window 3 --min-weight 2 --max-moves 500 --quiet
[ ! -e "$tmp/never.png" ] || fail "an unreached pattern was written"

expect_ok "$bin" module --out "$tmp/m" --camera-size 648x486
for f in module.json pattern.png pattern.json pattern_preview.png; do
  [ -s "$tmp/m/$f" ] || fail "module did not write $f"
done
expect_ok "$bin" describe --module "$tmp/m/module.json"
grep -q "cover" "$tmp/out" || fail "describe does not report the disparity coverage"

expect_ok "$bin" pattern --out "$tmp/p/small.png" --rows 6 --cols 40 --seed 3 --quiet
[ -s "$tmp/p/small.png" ] && [ -s "$tmp/p/small.json" ] || fail "pattern outputs missing"
grep -q '"valid": true' "$tmp/p/small.json" || fail "pattern report not valid"

# A module whose pattern file is truncated.
head -c 100 "$tmp/m/pattern.png" >"$tmp/m/cut.png"
sed 's/"pattern.png"/"cut.png"/' "$tmp/m/module.json" >"$tmp/m/cut.json"
expect_error "cut.png" "$bin" describe --module "$tmp/m/cut.json"

# Simulation (reduced module from above).
expect_ok "$bin" simulate frame --help
grep -q -- "--scene" "$tmp/out" || fail "simulate frame --help shows no --scene"
expect_ok "$bin" simulate frame --module "$tmp/m/module.json" --scene plane --distance-mm 90 \
  --out "$tmp/s/plane" --supersampling 1
for f in pattern.png texture.png truth_depth.tiff depth_preview.png scene.json; do
  [ -s "$tmp/s/plane/$f" ] || fail "simulate did not write $f"
done
grep -q '"seed"' "$tmp/s/plane/scene.json" || fail "scene.json lacks the seed"
cat >"$tmp/s/wall.json" <<'JSON'
{"type": "pipe_wall", "diameter_mm": 250, "material": "vitrified_clay",
 "features": [{"type": "joint", "station_mm": 20, "gap_mm": 4, "height_mm": 2, "offset_mm": 3}]}
JSON
expect_ok "$bin" simulate frame --module "$tmp/m/module.json" --scene "$tmp/s/wall.json" \
  --out "$tmp/s/wall" --supersampling 1 --bits 10
grep -q vitrified_clay "$tmp/s/wall/scene.json" || fail "scene file not used"
# The pipe-wall preset survives its own scene.json: re-rendered from it, the images are identical.
expect_ok "$bin" simulate frame --module "$tmp/m/module.json" --scene pipe-wall --out "$tmp/s/pw" \
  --supersampling 1
expect_ok "$bin" simulate frame --module "$tmp/m/module.json" --scene "$tmp/s/pw/scene.json" \
  --out "$tmp/s/pw2" --supersampling 1
for f in pattern.png texture.png truth_depth.tiff; do
  cmp -s "$tmp/s/pw/$f" "$tmp/s/pw2/$f" || fail "pipe-wall $f differs when rendered from its scene.json"
done
echo '{"type": "torus"}' >"$tmp/s/bad.json"
expect_error "'type'" "$bin" simulate frame --module "$tmp/m/module.json" --scene "$tmp/s/bad.json" --out "$tmp/s/x"
echo '{"type": "cylinder", "diameter_mm": 100, "axis_point_mm": [0, 0, 80]}' >"$tmp/s/outside.json"
expect_file_error "$tmp/s/outside.json" "axis_point_mm: puts the camera outside" \
  "$bin" simulate frame --module "$tmp/m/module.json" --scene "$tmp/s/outside.json" --out "$tmp/s/x"
expect_error "invalid value: --decentre-mm: puts the camera outside" "$bin" simulate frame \
  --module "$tmp/m/module.json" --scene cylinder --decentre-mm 0 200 --out "$tmp/s/x"
[ "$rc" -eq 2 ] || fail "an option value the library rejects exits $rc, not 2"
echo '{"type": "pipe_wall", "features": [{"type": "pit", "station_mm": 0, "height_mm": 2}]}' >"$tmp/s/pit.json"
expect_file_error "$tmp/s/pit.json" "features[0].radius_mm: must be > 0" \
  "$bin" simulate frame --module "$tmp/m/module.json" --scene "$tmp/s/pit.json" --out "$tmp/s/x"
expect_error "error" "$bin" simulate frame --module "$tmp/nothing.json" --out "$tmp/s/x"
# simulate run: input errors (the tiny run itself is checked by cli/run_format).
expect_ok "$bin" simulate run --help
grep -q -- "--preset" "$tmp/out" || fail "simulate run --help shows no --preset"
expect_error "--scenario FILE or --preset" "$bin" simulate run --out "$tmp/r"
expect_error "--preset" "$bin" simulate run --preset huge --out "$tmp/r"
printf '{"pipe": {"sections": [{"length_mm": 500}]}, "motoin": {}}' >"$tmp/typo.json"
expect_error "motoin" "$bin" simulate run --scenario "$tmp/typo.json" --out "$tmp/r"
printf '{"pipe": {"sections": [{"length_mm": 3000, "diameter_mm": 160}]}}' >"$tmp/narrow.json"
expect_error "does not fit" "$bin" simulate run --scenario "$tmp/narrow.json" --out "$tmp/r"
printf '{"pipe": {"sections": [{"length_mm": 500}, {"length_mm": 500}]}}' >"$tmp/nojoint.json"
expect_file_error "$tmp/nojoint.json" "pipe.joints: 2 sections need 1 joint" \
  "$bin" simulate run --scenario "$tmp/nojoint.json" --out "$tmp/r"
printf '{"pipe": {"sections": [{"length_mm": 3000}]}, "motion": {"speed_mm_s": -5}}' >"$tmp/slow.json"
expect_file_error "$tmp/slow.json" "motion.speed_mm_s: a crawler's speed must be 1..1000 mm/s" \
  "$bin" simulate run --scenario "$tmp/slow.json" --out "$tmp/r"
printf '{"pipe": {"sections": [{"length_mm": 3000}]}, "rig": {"stagger_mm": 200}, "motion": {"start_station_mm": 700}}' >"$tmp/long_rig.json"
expect_file_error "$tmp/long_rig.json" "rig.stagger_mm" \
  "$bin" simulate run --scenario "$tmp/long_rig.json" --out "$tmp/r"
printf '{"pipe": {"sections": [{"length_mm": 500, "material": "wood"}]}}' >"$tmp/wood.json"
expect_error "wood" "$bin" simulate run --scenario "$tmp/wood.json" --out "$tmp/r"
printf '{"pipe": ' >"$tmp/cut.json"
expect_error "cut.json" "$bin" simulate run --scenario "$tmp/cut.json" --out "$tmp/r"

# Reconstruction of the simulated plane.
expect_ok "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/s/plane/pattern.png" \
  --texture "$tmp/s/plane/texture.png" --out "$tmp/r/plane"
for f in cloud.ply depth.tiff depth.png report.json; do
  [ -s "$tmp/r/plane/$f" ] || fail "reconstruct did not write $f"
done
grep -q '"points"' "$tmp/r/plane/report.json" || fail "report lacks points"
grep -q '"lost_spots_found"' "$tmp/r/plane/report.json" || fail "report lacks lost_spots_found"
expect_ok "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/s/plane/pattern.png" \
  --no-lost-spots --out "$tmp/r/plane_nolost"
grep -q '"lost_spots_found": 0,' "$tmp/r/plane_nolost/report.json" ||
  fail "--no-lost-spots still looked for lost spots"
grep -q '"cut_by_step"' "$tmp/r/plane/report.json" || fail "report lacks rejected.cut_by_step"
expect_ok "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/s/plane/pattern.png" \
  --no-cut-spots --out "$tmp/r/plane_nocut"
grep -q '"cut_by_step": 0,' "$tmp/r/plane_nocut/report.json" ||
  fail "--no-cut-spots still dropped spots"
expect_ok "$bin" evaluate plane --cloud "$tmp/r/plane/cloud.ply" --truth "$tmp/s/plane/scene.json" \
  --out "$tmp/r/plane_eval"
grep -q "RMS" "$tmp/out" || fail "evaluate prints no RMS"
for f in residuals residuals_smoothed truth_residuals truth_residuals_smoothed; do
  [ -s "$tmp/r/plane_eval/$f.png" ] || fail "evaluate plane --out wrote no $f.png"
done
grep -Eq "plane at (89\.9[5-9]|90\.0[0-4])" "$tmp/out" || fail "evaluate does not find the 90 mm plane: $(cat "$tmp/out")"
expect_error "cylinder\|points" "$bin" evaluate cylinder --cloud "$tmp/r/plane/cloud.ply" --inner-fraction 0.05
expect_error "expected one of plane, cylinder, rgbd, registration, model, inspection, calibration, got sphere" "$bin" evaluate sphere --cloud "$tmp/r/plane/cloud.ply"
# Blank, wrong-size, truncated and non-image inputs: one-line errors, no crash.
"$bin" simulate frame --module "$tmp/m/module.json" --scene plane --distance-mm 2000 \
  --out "$tmp/s/far" --supersampling 1 >/dev/null 2>&1
expect_error "no spot pattern" "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/s/far/pattern.png" --out "$tmp/r/far"
expect_error "but the module's camera is" "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/m/pattern.png" --out "$tmp/r/x"
head -c 2000 "$tmp/s/plane/pattern.png" >"$tmp/r/cut.png"
expect_error "truncated" "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/r/cut.png" --out "$tmp/r/x"
expect_error "not a PNG, TIFF or JPEG image" "$bin" reconstruct --module "$tmp/m/module.json" --image "$tmp/m/module.json" --out "$tmp/r/x"

# Pose graphs.
data=${SEWER3D_DATA:?set SEWER3D_DATA to tests/data}
expect_ok "$bin" posegraph --in "$data/posegraph/tinyGrid3D.g2o" --out "$tmp/g/tiny.g2o" --threads 1
grep -q "final cost" "$tmp/out" || fail "posegraph prints no final cost"
[ "$(grep -c VERTEX_SE3:QUAT "$tmp/g/tiny.g2o")" -eq 9 ] || fail "posegraph output lacks vertices"
expect_ok "$bin" posegraph --in "$tmp/g/tiny.g2o" --out "$tmp/g/again.g2o" --init odometry --robust huber:2
expect_ok "$bin" posegraph --in "$data/posegraph/tinyGrid3D.g2o" --out "$tmp/g/cert.g2o" --certify
grep -q "of the global optimum (relative gap): certified" "$tmp/out" || fail "posegraph --certify does not certify tinyGrid3D"
expect_ok "$bin" posegraph --in "$data/posegraph/tinyGrid3D.g2o" --out "$tmp/g/cert.g2o" --certify --robust huber:2
grep -q "certificate not applicable: robust loss" "$tmp/out" || fail "posegraph --certify with a robust loss"
expect_error "huber" "$bin" posegraph --in "$tmp/g/tiny.g2o" --out "$tmp/g/x.g2o" --robust cauchy:1
expect_error "--init" "$bin" posegraph --in "$tmp/g/tiny.g2o" --out "$tmp/g/x.g2o" --init magic
head -3 "$data/posegraph/tinyGrid3D.g2o" >"$tmp/g/cut.g2o"
echo "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 100" >>"$tmp/g/cut.g2o"
expect_error "line 4" "$bin" posegraph --in "$tmp/g/cut.g2o" --out "$tmp/g/x.g2o"

# calibrate camera: real images, a board-less image skipped, too few views, mixed sizes.
boards="$data/opencv-chessboard"
mkdir -p "$tmp/c"
for size in 640x480 320x240; do
  "$bin" module --out "$tmp/c/m$size" --camera-size "$size" >/dev/null
  "$bin" simulate frame --module "$tmp/c/m$size/module.json" --scene plane --supersampling 1 \
    --out "$tmp/c/plain$size" >/dev/null
done
expect_ok "$bin" calibrate camera --images "$boards"/left0[1-4].jpg "$tmp/c/plain640x480/texture.png" --board 9x6 \
  --square-mm 25 --out "$tmp/c/camera.json"
grep -q "texture.png: 9x6 board not found, skipped" "$tmp/out" || fail "calibrate camera did not list the board-less image"
grep -q '"rms_px"' "$tmp/c/camera.json" || fail "calibrate camera wrote no rms_px"
[ -s "$tmp/c/left03_corners.png" ] || fail "calibrate camera wrote no corner picture"
expect_error "at least 3" "$bin" calibrate camera --images "$boards/left01.jpg" "$boards/left02.jpg" --out "$tmp/c/x.json"
expect_error "one camera, one size" "$bin" calibrate camera --images "$boards/left01.jpg" \
  "$tmp/c/plain320x240/texture.png" --out "$tmp/c/x.json"
expect_error "COLSxROWS" "$bin" calibrate camera --images "$boards/left01.jpg" --board nine --out "$tmp/c/x.json"
printf 'x' >"$tmp/c/cut.png"
expect_error "cut.png" "$bin" calibrate camera --images "$boards/left01.jpg" "$tmp/c/cut.png" --out "$tmp/c/x.json"

# simulate calibration: rendered board captures a calibration reads.
expect_ok "$bin" simulate calibration --module "$tmp/c/m640x480/module.json" --poses 3 --supersampling 1 \
  --texture-supersampling 1 --out "$tmp/c/sim"
for f in board.json truth/module.json truth/pattern.png truth/poses.json pose_00/texture.png pose_02/pattern.png; do
  [ -s "$tmp/c/sim/$f" ] || fail "simulate calibration did not write $f"
done
expect_ok "$bin" describe --module "$tmp/c/sim/truth/module.json"  # the truth module loads on its own
expect_error "COLSxROWS" "$bin" simulate calibration --module "$tmp/c/m640x480/module.json" --board 9 --out "$tmp/c/s2"

# evaluate calibration: a module with its standard deviations against the captures' truth. The
# true module itself, given the calibration member calibrate module writes, lies 0 σ off.
expect_error "'calibration' member" "$bin" evaluate calibration --captures "$tmp/c/sim" \
  --module "$tmp/c/sim/truth/module.json"
mkdir -p "$tmp/c/sigma" && cp "$tmp/c/sim/truth/pattern.png" "$tmp/c/sigma/"
sed 's/^{/{"calibration": {"sigma": {"camera": {"fx": 0.2, "fy": 0.2, "cx": 0.1, "cy": 0.1}, "projector": {"fx": 0.2, "fy": 0.2, "cx": 0.1, "cy": 0.1}, "baseline_mm": 0.01, "rotation_deg": 0.01}},/' \
  "$tmp/c/sim/truth/module.json" >"$tmp/c/sigma/module.json"
expect_ok "$bin" evaluate calibration --captures "$tmp/c/sim" --module "$tmp/c/sigma/module.json" \
  --out "$tmp/c/sigma/evaluation.json"
grep -q "within 2 σ: 10 of 10 parameters of the true module, 10 of the nearest" "$tmp/out" ||
  fail "evaluate calibration of the true module: $(tail -1 "$tmp/out")"
grep -q '"within_2_sigma": 10' "$tmp/c/sigma/evaluation.json" || fail "evaluate calibration wrote no JSON"
expect_error "truth/poses.json" "$bin" evaluate calibration --captures "$tmp/c/m640x480" \
  --module "$tmp/c/sigma/module.json"
expect_error "does not apply" "$bin" evaluate calibration --captures "$tmp/c/sim" \
  --module "$tmp/c/sigma/module.json" --run "$tmp/c/sim"

# calibrate module: the capture folder must hold at least 3 poses.
mkdir -p "$tmp/c/few" && cp -r "$tmp/c/sim/pose_00" "$tmp/c/few/"
expect_error "at least 3" "$bin" calibrate module --captures "$tmp/c/few" --board 9x6 --out "$tmp/c/mod.json"
expect_error "--captures" "$bin" calibrate module --captures "$tmp/c/none" --out "$tmp/c/mod.json"

# rgbd: the RGB-D stage over a tiny run; a second run skips everything; bad images fail alone.
expect_ok "$bin" rgbd --help
grep -q -- "--threads" "$tmp/out" || fail "rgbd --help shows no --threads"
expect_ok "$bin" simulate run --preset tiny --out "$tmp/rg/run" --quiet
expect_ok "$bin" rgbd "$tmp/rg/run" --out "$tmp/rg/ws" --quiet
for k in 0 1 2 3 4 5; do
  for c in 000000 000001; do
    for f in color.png depth.tiff cloud.ply report.json; do
      [ -s "$tmp/rg/ws/rgbd/m$k/${c}_$f" ] || fail "rgbd did not write m$k/${c}_$f"
    done
  done
done
grep -q '"color": "texture triplet: deblurred' "$tmp/rg/ws/workspace.json" ||
  fail "workspace.json does not say where colour comes from"
expect_ok "$bin" rgbd "$tmp/rg/run" --out "$tmp/rg/ws" --quiet
grep -q "0 done, 12 skipped" "$tmp/out" || fail "rgbd run again did not skip everything: $(cat "$tmp/out")"
expect_error "--force" "$bin" rgbd "$tmp/rg/run" --out "$tmp/rg/ws" --quiet --max-edge-steps 4
[ -s "$tmp/rg/ws/rgbd/m0/000000_report.json" ] || fail "refused rgbd removed outputs"
cut=$tmp/rg/run/images/m3/000001_pattern.png
head -c 2000 "$cut" >"$tmp/rg/cut.png" && mv "$tmp/rg/cut.png" "$cut"
# A bad image costs its acquisition only: a warning naming the file, the rest processed.
"$bin" rgbd "$tmp/rg/run" --out "$tmp/rg/ws2" --quiet >"$tmp/out" 2>"$tmp/err"
rc=$?
[ "$rc" -eq 0 ] || fail "rgbd with one truncated image exited $rc: $(cat "$tmp/err")"
grep -q "000001_pattern.png: cannot decode image: truncated PNG" "$tmp/err" ||
  fail "rgbd does not name the truncated image: $(cat "$tmp/err")"
[ -s "$tmp/rg/ws2/rgbd/m3/000000_report.json" ] || fail "rgbd did not process the other acquisitions"
[ -e "$tmp/rg/ws2/rgbd/m3/000001_report.json" ] && fail "rgbd wrote a report for the bad acquisition"
grep -q "$cut" "$tmp/rg/ws2/rgbd/report.json" || fail "rgbd/report.json does not list the bad image"
expect_error "no_run: is not a run folder" "$bin" rgbd "$tmp/rg/no_run" --out "$tmp/rg/ws4" --quiet
"$bin" rgbd "$tmp/rg/no_run" --out "$tmp/rg/ws4" --quiet >/dev/null 2>&1
[ $? -eq 3 ] || fail "rgbd on a folder that is no run did not exit 3"

# process: the chain of stages; bad input is refused before anything runs, a failed stage stops it.
expect_ok "$bin" process --help
for opt in --start-station-mm --resolution-mm --threads --force --quiet; do
  grep -q -- "$opt" "$tmp/out" || fail "process --help shows no $opt"
done
expect_ok "$bin" demo --help
grep -q -- "--out" "$tmp/out" || fail "demo --help shows no --out"
expect_error "no_run: is not a run folder" "$bin" process "$tmp/rg/no_run" --out "$tmp/rg/ws5" --quiet
[ "$rc" -eq 3 ] || fail "process on a folder that is no run exited $rc, not 3"
expect_error "--resolution-mm" "$bin" process "$tmp/rg/run" --out "$tmp/rg/ws5" --resolution-mm 0
[ "$rc" -eq 2 ] || fail "process --resolution-mm 0 exited $rc, not 2"
expect_error "--resolution-mm" "$bin" process "$tmp/rg/run" --out "$tmp/rg/ws5" --resolution-mm abc
[ "$rc" -eq 2 ] || fail "process --resolution-mm abc exited $rc, not 2"
expect_error "--start-station-mm: must be a number, got NaN" \
  "$bin" process "$tmp/rg/run" --out "$tmp/rg/ws5" --start-station-mm nan
[ "$rc" -eq 2 ] || fail "process --start-station-mm nan exited $rc, not 2"
[ -e "$tmp/rg/ws5" ] && fail "a refused process wrote its workspace"
# (process over a run with bad images: pipeline/process_chain_sim.)

# model: refused without a registration (exit 3, one line naming poses.csv) or with a bad grid.
expect_ok "$bin" model --help
for opt in --resolution-mm --start-station-mm --nominal-diameter-mm --straight --keep-tiles; do
  grep -q -- "$opt" "$tmp/out" || fail "model --help shows no $opt"
done
expect_error "poses.csv: missing: run the register stage first" \
  "$bin" model "$tmp/rg/run" --out "$tmp/rg/ws" --quiet
[ "$rc" -eq 3 ] || fail "model without a registration exited $rc, not 3"
expect_error "--resolution-mm" "$bin" model "$tmp/rg/run" --out "$tmp/rg/ws" --resolution-mm 0 --quiet
[ "$rc" -eq 2 ] || fail "model --resolution-mm 0 exited $rc, not 2"
expect_error "--start-station-mm" "$bin" model "$tmp/rg/run" --out "$tmp/rg/ws" --start-station-mm nan
[ "$rc" -eq 2 ] || fail "model --start-station-mm nan exited $rc, not 2"
expect_error "model.json" "$bin" evaluate model --run "$tmp/rg/run" --workspace "$tmp/rg/ws"
[ "$rc" -eq 3 ] || fail "evaluate model without a model exited $rc, not 3"

# inspect and its evaluation need the model and the inspection: one line naming the file, exit 3
expect_error "model.json" "$bin" inspect "$tmp/rg/run" --out "$tmp/rg/ws" --quiet
[ "$rc" -eq 3 ] || fail "inspect without a model exited $rc, not 3"
expect_error "--intrusion-mm" "$bin" inspect "$tmp/rg/run" --out "$tmp/rg/ws" --intrusion-mm 0
[ "$rc" -eq 2 ] || fail "inspect --intrusion-mm 0 exited $rc, not 2"
expect_error "--crack-min-length-mm" "$bin" inspect "$tmp/rg/run" --out "$tmp/rg/ws" --crack-min-length-mm 0
[ "$rc" -eq 2 ] || fail "inspect --crack-min-length-mm 0 exited $rc, not 2"
expect_ok "$bin" inspect --help
grep -q -- "--no-texture-cracks" "$tmp/out" || fail "inspect --help shows no --no-texture-cracks"
expect_error "observations.json" "$bin" evaluate inspection --run "$tmp/rg/run" --workspace "$tmp/rg/ws"
[ "$rc" -eq 3 ] || fail "evaluate inspection without an inspection exited $rc, not 3"

# report: a workspace without a model still gets its page, and one warning line naming model.json
mkdir -p "$tmp/rep/ws"
"$bin" report "$tmp/rg/run" --out "$tmp/rep/ws" --quiet >"$tmp/out" 2>"$tmp/err" ||
  fail "report without a model exited $?"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "report without maps: .*model.json" "$tmp/err" ||
  fail "report without a model: no one-line warning naming model.json: $(cat "$tmp/err")"
grep -q "The model could not be read" "$tmp/rep/ws/report/index.html" 2>/dev/null ||
  fail "report without a model: no page with the note"
expect_file_error "$tmp/rep/none" "workspace folder not found" "$bin" report "$tmp/rg/run" --out "$tmp/rep/none"

if [ "$failures" -ne 0 ]; then echo "$failures CLI check(s) failed"; exit 1; fi
echo "all CLI checks passed"
