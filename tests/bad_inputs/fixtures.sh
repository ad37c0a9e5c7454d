#!/usr/bin/env bash
# Fixtures of the bad-input table, written into folder $1 (run.sh's $T). $S is the binary.
set -eu
T=$1
cd "$T"
python3 "$(dirname "$0")/fixtures.py" "$T"
mkfifo fifo
mkdir dir
"$S" module --out m --camera-size 648x486 >/dev/null
# A tiny run's scenario: 40 mm of travel at 160 px, so a simulation takes about a second.
cat >scenario_ok.json <<'JSON'
{"camera_width": 160, "motion": {"travel_mm": 40, "start_station_mm": 300},
 "truth_depth": "none",
 "pipe": {"sections": [{"length_mm": 600, "diameter_mm": 300}, {"length_mm": 600, "diameter_mm": 300}],
          "joints": [{"id": "J1", "gap_mm": 5, "gap_depth_mm": 3, "offset_mm": 2, "offset_clock_h": 6}],
          "features": [{"id": "C1", "type": "connection", "station_mm": 300, "clock_h": 2,
                        "diameter_mm": 100, "intrusion_mm": 10, "wall_mm": 12}]}}
JSON
# json_with SOURCE DEST KEY=JSON...: SOURCE with members replaced (dotted keys, list indices).
json_with() {
  python3 - "$@" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for arg in sys.argv[3:]:
    key, value = arg.split("=", 1)
    node = d
    parts = key.split(".")
    for p in parts[:-1]:
        node = node[int(p)] if isinstance(node, list) else node[p]
    last = parts[-1]
    node[int(last) if isinstance(node, list) else last] = json.loads(value)
json.dump(d, open(sys.argv[2], "w"))
PY
}
scenario_with() { json_with scenario_ok.json "$@"; }
scenario_with clock_huge.json 'pipe.features.0.clock_h=1e6'
scenario_with slow.json 'motion.speed_mm_s=1e-6'
scenario_with far.json 'motion.travel_mm=1e9'
scenario_with seed_big.json 'seed=9007199254740993'
scenario_with nan_speed.json 'motion.speed_mm_s=NaN'
scenario_with station_beyond.json 'pipe.features.0.station_mm=5000'
scenario_with id_twice.json 'pipe.features.0.id="J1"'
# Modules with degenerate geometry.
module_with() { json_with m/module.json "$@"; }
module_with m/zero_baseline.json 'projector_from_camera.translation_mm=[0,0,0]'
module_with m/huge_baseline.json 'projector_from_camera.translation_mm=[-1e6,0,0]'
module_with m/tiny_focal.json 'camera.fx=1e-6' 'camera.fy=1e-6'
module_with m/k1_neg10.json 'camera.k=[-10,0,0]'
module_with m/tiny_pitch.json 'pattern.pitch_px=0.001'
module_with m/huge_matrix.json 'pattern.matrix="../huge_matrix.png"'
module_with m/huge_header.json 'pattern.matrix="../huge_header.png"'
module_with m/fifo_matrix.json 'pattern.matrix="../fifo"'
# A pattern capture of the small module, 8- and 12-bit.
"$S" simulate frame --module m/module.json --scene plane --distance-mm 110 --supersampling 1 \
  --out frame8 >/dev/null
"$S" simulate frame --module m/module.json --scene plane --distance-mm 110 --supersampling 1 \
  --bits 12 --out frame12 >/dev/null
# Broken module files.
echo '[]' >m/array.json
: >m/empty.json
head -c 300 /dev/urandom >m/garbage.json
module_with m/fx_text.json 'camera.fx="433"'
module_with m/fx_huge.json 'camera.fx=1e308'
module_with m/width_neg.json 'camera.width=-5'
module_with m/matrix_dir.json 'pattern.matrix="../dir"'
module_with m/matrix_text.json 'pattern.matrix="module.json"'
module_with m/principal_out.json 'camera.cx=5000'
module_with m/width_u64.json 'camera.width=18446744073709551615'
python3 -c "import json; d=json.load(open('m/module.json')); del d['camera']; json.dump(d, open('m/no_camera.json','w'))"
printf '%s trailing' "$(cat m/module.json)" >m/trailing.json
# Broken scenarios.
echo '{}' >no_pipe.json
scenario_with unknown_member.json 'motion.sped_mm_s=100'
scenario_with no_sections.json 'pipe.sections=[]' 'pipe.joints=[]'
scenario_with diameter_huge.json 'pipe.sections.0.diameter_mm=1e9'
scenario_with travel_neg.json 'motion.travel_mm=-5'
scenario_with clock_neg.json 'pipe.features.0.clock_h=-1'
scenario_with width_float.json 'camera_width=160.5'
scenario_with width_huge.json 'camera_width=10000000000'
scenario_with seed_neg.json 'seed=-3'
scenario_with km_pipe.json 'pipe.sections.0.length_mm=1500000' 'pipe.sections.1.length_mm=400000' \
  'motion.travel_mm=1800000' 'camera_width=8192'
printf '{"pipe": {"sections": [{"length_mm": NaN, "diameter_mm": 300}]}}' >nan_literal.json
# Broken pose graphs.
: >empty.g2o
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0\n' >short_vertex.g2o
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nEDGE_SE3:QUAT 0 7 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n' >missing_node.g2o
printf 'VERTEX_SE3:QUAT 0 nan 0 0 0 0 0 1\n' >nan_vertex.g2o
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 0\n' >zero_quat.g2o
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n\0VERTEX_SE3:QUAT 1 0 0 0 0 0 0 1\n' >nul.g2o
# Two vertices and an edge, and a third vertex no edge reaches.
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\nVERTEX_SE3:QUAT 2 5 0 0 0 0 0 1\nEDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\nFIX 0\n' >apart.g2o
ln -s loop loop
# Broken clouds.
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n' >no_end_header.ply
printf 'ply\nformat ascii 1.0\nelement vertex 1000000000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n' >count_huge.ply
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar int x\nend_header\n1 2\n' >list_vertex.ply
# Broken images: a pattern capture with one IDAT byte flipped, a text file named .png.
python3 - <<'PY'
b = bytearray(open("frame8/pattern.png", "rb").read())
at = b.find(b"IDAT") + 40
b[at] ^= 0xFF
open("crc_bad.png", "wb").write(b)
PY
echo 'not an image' >text.png
"$S" module --out m_big --camera-size 1296x972 >/dev/null
# A finished tiny run, and copies broken.
"$S" simulate run --scenario scenario_ok.json --out run_ok --quiet >/dev/null
mkdir -p not_a_run && echo x >not_a_run/file.txt
# run_ok copied with one file broken: run_<what>.
broken_run() {
  cp -r run_ok "run_$1"
  case "$2" in
    *.csv) sed -i "$3" "run_$1/$2" ;;
    *) json_with "run_ok/$2" "run_$1/$2" "${@:3}" ;;
  esac
}
broken_run clock rig.json 'modules.0.clock_h=13'
broken_run names rig.json 'modules.1.name="m0"'
broken_run period run.json 'acquisition_period_s=-0.5'
broken_run count run.json 'images=36' 'acquisitions=2'
broken_run odometry odometry.csv '3s/,.*/,1e308/'
broken_run acq_neg run.json 'acquisitions=-2'
broken_run counter_huge acquisitions.csv '2s/^0,0,/0,1000000000000,/'
broken_run crlf acquisitions.csv 's/$/\r/'
broken_run rig_v2 rig.json 'version=2'
scenario_with slip_beyond.json 'odometry={"slips": [{"station_mm": 1e6, "length_mm": 10, "fraction": 0.5}]}'
# Scene files: a frame's scene.json with its render options or features broken.
"$S" simulate frame --module m/module.json --scene pipe-wall --supersampling 1 --out fpw >/dev/null
json_with frame8/scene.json scene_bits16.json 'render.bits=16'
json_with fpw/scene.json scene_pit_deep.json 'scene.features.2.depth_mm=1e6'
printf '{"type": "cylinder", "diameter_mm": 1e400}' >scene_overflow.json
scenario_with connection_wide.json 'pipe.features.0.diameter_mm=1000'
printf 'ply\nformat ascii 1.0\nelement vertex -5\nproperty float x\nproperty float y\nproperty float z\nend_header\n' >neg_count.ply
printf '\xef\xbb\xbfVERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nFIX 0\n' >bom.g2o
mkfifo fifo_out.g2o
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nFIX 0\n' >one.g2o
"$S" simulate calibration --module m/module.json --poses 1 --out calib --supersampling 1 \
  --texture-supersampling 1 >/dev/null 2>&1
: >zero.tiff
mkdir -p foreign_cal/pose_00
# Session 26 (fifth probe).
json_with m/module.json m/offset_huge.json 'pattern.offset_px=[-1e9,0]'
json_with m/module.json m/k_huge.json 'camera.k=[1e10,0,0]'
python3 -c "import sys; t = open('m/module.json').read(); open('m/nul.json', 'w').write(t[:100] + chr(0) + t[100:])"
json_with frame8/scene.json scene_psf_huge.json 'render.projector_psf_px=1e6'
json_with fpw/scene.json scene_joint_offset.json 'scene.features.0.offset_mm=1000'
json_with fpw/scene.json scene_axis_big.json 'scene.axis=[0,1e308,1e308]'
mkfifo pfifo.json
mkdir -p rfifo && mkfifo rfifo/report.json
printf 'VERTEX_SE3:QUAT 0 1e300 0 0 0 0 0 1\nFIX 0\n' >far.g2o
broken_run exposure acquisitions.csv '2s/^\([^,]*,[^,]*,[^,]*,[^,]*,\)[^,]*,/\11000000,/'
broken_run same_file acquisitions.csv '3s|,[^,]*$|,'"$(sed -n 2p run_ok/acquisitions.csv | sed 's/.*,//')"'|'
broken_run times_zero acquisitions.csv '2,$s/^\([^,]*,[^,]*,[^,]*,\)[^,]*,/\10.000000,/'
scenario_with nominal_far.json 'capture={"nominal_diameter_mm": 1000}'
scenario_with gap_deep.json 'pipe.joints.0.gap_depth_mm=500'
