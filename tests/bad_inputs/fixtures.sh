#!/usr/bin/env bash
# Fixtures of the bad-input table, written into folder $1 (run.sh's $T). $S is the binary.
set -eu
T=$1
cd "$T"
python3 "$(dirname "$0")/fixtures.py" "$T"
mkfifo fifo
mkdir dir
"$S" module --out m --camera-size 648x486 >/dev/null
"$S" module --out m_full >/dev/null  # the default, full-size module
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
scenario_with start_beyond.json 'motion.start_station_mm=1200' 'motion.travel_mm=20'
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
# A capture whose image lies 8 px to the right of where the module says (cx + 8).
module_with m/cx8.json "camera.cx=$(python3 -c "import json; print(json.load(open('m/module.json'))['camera']['cx'] + 8)")"
"$S" simulate frame --module m/cx8.json --scene plane --distance-mm 110 --supersampling 1 \
  --out frame_cx8 >/dev/null
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
broken_run clock_typo rig.json 'modules.0.clock_hh=3'
broken_run incl_zero inclinometer.csv '3s/,.*/,0,0,0/'
broken_run incl_back inclinometer.csv '4s/^[^,]*,/0.01,/'
scenario_with slip_beyond.json 'odometry={"slips": [{"station_mm": 1e6, "length_mm": 10, "fraction": 0.5}]}'
scenario_with slips_overlap.json 'odometry={"slips": [{"station_mm": 300, "length_mm": 20, "fraction": 0.7}, {"station_mm": 310, "length_mm": 20, "fraction": 0.6}]}'
scenario_with crack_around.json 'pipe.features.0={"id": "K1", "type": "crack", "station_mm": 600, "clock_h": 3, "length_mm": 2000, "width_mm": 1, "depth_mm": 2, "angle_deg": 90}'
scenario_with odo_noise.json 'odometry={"noise_mm": 1000}'
scenario_with incl_noise.json 'inclinometer={"noise_deg": 5}'
printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\nVERTEX_SE3:QUAT 2 2 0 0 0 0 0 1\nEDGE_SE3:QUAT 0 1 1 0 0 1 0.001 0 0 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\nEDGE_SE3:QUAT 1 2 1 0 0 0.9999 0.01 0 0 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n' >wxyz.g2o
scenario_with crack_long.json 'pipe.features.0={"id": "K1", "type": "crack", "station_mm": 600, "clock_h": 3, "length_mm": 5000, "width_mm": 1, "depth_mm": 2}'
scenario_with deposit_crown.json 'pipe.features.0={"id": "D1", "type": "deposit", "station_mm": 300, "clock_h": 12, "length_mm": 100, "height_mm": 10}'
scenario_with wet_no_width.json 'pipe.features.0={"id": "W1", "type": "wet", "station_mm": 300, "clock_h": 6, "length_mm": 100}'
# Scene files: a frame's scene.json with its render options or features broken.
scene_with() { json_with frame8/scene.json "$@"; }
"$S" simulate frame --module m/module.json --scene pipe-wall --supersampling 1 --out fpw >/dev/null
scene_with scene_bits16.json 'render.bits=16'
scene_with scene_dist_tiny.json 'scene.distance_mm=0.001'
scene_with scene_f0.json 'render.camera_f_number=0'
scene_with scene_module_gone.json 'module="gone/module.json"'
scene_with scene_sensor_tiny.json 'render.sensor_width_mm=1e-6'
json_with fpw/scene.json scene_type_plane.json 'scene.type="plane"'
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
# Calibration truths for evaluate calibration: a realism no profile has; poses that are not poses.
mkdir -p calib_realism/truth calib_pose/truth
cp calib/truth/module.json calib/truth/pattern.png calib_realism/truth/
cp calib/truth/module.json calib/truth/pattern.png calib_pose/truth/
json_with calib/truth/poses.json calib_realism/truth/poses.json 'realism="fancy"'
json_with calib/truth/poses.json calib_pose/truth/poses.json 'poses.0.camera_from_board.rotation=[1,0,0,0,1,0,0,0,2]'
# Session 26 (fifth probe).
json_with m/module.json m/offset_huge.json 'pattern.offset_px=[-1e9,0]'
json_with m/module.json m/k_huge.json 'camera.k=[1e10,0,0]'
# The projector above the camera, not beside it: the disparity runs along the 6-row side.
json_with m/module.json m/baseline_y.json "projector_from_camera.translation_mm=[0,-77.6,0]"
json_with m/module.json m/fy_ten.json "camera.fy=4334"
python3 -c "import sys; t = open('m/module.json').read(); open('m/nul.json', 'w').write(t[:100] + chr(0) + t[100:])"
scene_with scene_psf_huge.json 'render.projector_psf_px=1e6'
json_with fpw/scene.json scene_joint_offset.json 'scene.features.0.offset_mm=1000'
json_with fpw/scene.json scene_axis_big.json 'scene.axis=[0,1e308,1e308]'
# Probe 23: a realism profile beside every member it sets (a written file); members named as
# the file spells them; per-shot members in a scenario's render; unknown scene members.
scene_with scene_realism_dead.json 'render.realism="paper"'
scene_with scene_gain_neg.json 'render.spot_gain_sigma=-1'
scene_with scene_wavelength.json 'render.speckle_wavelength_nm=0'
scene_with scene_centre_neg.json 'render.calibration_centre_px=-1'
scene_with scene_top_bits.json 'bits=12'
scene_with scene_tilt_typo.json 'scene.tilt_degs=30'
printf '{"type": "plane", "distance_mm": 150, "realism": "paper"}' >scene_top_realism.json
# Stage outputs without workspace.json (removed, or copied in).
mkdir -p ws_unrecorded/registration
# Probe 24: an empty joint id; a scenario's camera_width beside --module's camera.
scenario_with joint_id_empty.json 'pipe.joints.0.id=""'
# (a 160 px module and 10 mm of travel: the case renders, and the sanitizer build is slow)
scenario_with width_320.json 'camera_width=320' 'motion.travel_mm=10'
"$S" module --out m160 --camera-size 160x120 >/dev/null
scenario_with scenario_render_speed.json 'render={"speed_mm_s": 100}'
scenario_with scenario_render_exposure.json 'render={"exposure_ms": 5}'
mkfifo pfifo.json
mkdir -p rfifo && mkfifo rfifo/report.json
printf 'VERTEX_SE3:QUAT 0 1e300 0 0 0 0 0 1\nFIX 0\n' >far.g2o
broken_run exposure acquisitions.csv '2s/^\([^,]*,[^,]*,[^,]*,[^,]*,\)[^,]*,/\11000000,/'
broken_run same_file acquisitions.csv '3s|,[^,]*$|,'"$(sed -n 2p run_ok/acquisitions.csv | sed 's/.*,//')"'|'
broken_run times_zero acquisitions.csv '2,$s/^\([^,]*,[^,]*,[^,]*,\)[^,]*,/\10.000000,/'
scenario_with nominal_far.json 'capture={"nominal_diameter_mm": 1000}'
scenario_with gap_deep.json 'pipe.joints.0.gap_depth_mm=500'
scenario_with crack_wide.json 'pipe.features.0={"id": "K1", "type": "crack", "station_mm": 300, "clock_h": 2, "length_mm": 80, "width_mm": 500, "depth_mm": 2}'
scenario_with triplet_long.json 'capture={"triplet_interval_ms": 10000}'
# Session 27 (probe 5's leftovers).
# white_png PNG: the 8-bit PNG replaced by an all-white one of its size and colour type.
white_png() {
  python3 - "$1" <<'PY'
import struct, sys, zlib
path = sys.argv[1]
w, h, depth, colour = struct.unpack(">IIBB", open(path, "rb").read()[16:26])
channels = {0: 1, 2: 3}[colour]
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
rows = b"".join(b"\0" + b"\xff" * (channels * w) for _ in range(h))
open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour, 0, 0, 0))
                       + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
PY
}
broken_run swapped rig.json 'modules.0.name="m1"' 'modules.1.name="m0"'
cp -r run_ok run_odo_ms
awk -F, 'NR == 1 { print; next } { printf "%.3f,%s\n", $1 * 1000, $2 }' run_ok/odometry.csv \
  >run_odo_ms/odometry.csv
# One module, two acquisitions (100 mm of travel), at the smallest size rgbd decodes (648 px)
# for what compares counters.
python3 -c "import json; s = json.load(open('scenario_ok.json')); s['motion']['travel_mm'] = 100; \
s['camera_width'] = 648; s['rig'] = {'modules': 1}; s['render'] = {'supersampling': 1}; \
json.dump(s, open('scenario_two.json', 'w'))"
"$S" simulate run --scenario scenario_two.json --out run_two --quiet >/dev/null
# The same with truth albedo, processed: an evaluation that succeeds (evaluate rgbd needs it).
python3 -c "import json; s = json.load(open('scenario_two.json')); s['truth_albedo'] = True; \
json.dump(s, open('scenario_two_albedo.json', 'w'))"
"$S" simulate run --scenario scenario_two_albedo.json --out run_albedo --quiet >/dev/null
"$S" rgbd run_albedo --out ws_albedo --quiet >/dev/null 2>&1
cp -r run_two run_stuck
cp run_stuck/images/m0/000000_pattern.png run_stuck/images/m0/000001_pattern.png
cp -r run_two run_white
white_png run_white/images/m0/000001_texture_before.png
cp -r run_two run_replaced
# The run's pattern matrix with every spot doubled to the right: spots touch.
cp -r run_ok run_touching
python3 - run_touching/pattern.png <<'PY'
import struct, sys, zlib
path = sys.argv[1]
b = open(path, "rb").read()
w, h, depth, colour = struct.unpack(">IIBB", b[16:26])
assert depth == 8 and colour == 0, (depth, colour)
data, at = b"", 8
while at < len(b):
    n, kind = struct.unpack(">I4s", b[at:at + 8])
    if kind == b"IDAT":
        data += b[at + 8:at + 8 + n]
    at += 12 + n
raw = zlib.decompress(data)
rows, prior = [], [0] * w
for r in range(h):  # undo the PNG row filters (one byte per pixel)
    kind, line, px = raw[r * (w + 1)], raw[r * (w + 1) + 1:(r + 1) * (w + 1)], []
    for c in range(w):
        a, b, cc = px[c - 1] if c else 0, prior[c], prior[c - 1] if c else 0
        p = a + b - cc
        paeth = a if abs(p - a) <= min(abs(p - b), abs(p - cc)) else (b if abs(p - b) <= abs(p - cc) else cc)
        px.append((line[c] + [0, a, b, (a + b) // 2, paeth][kind]) & 0xFF)
    prior = px
    rows.append(b"\0" + bytes(max(px[c], px[c - 1]) for c in range(w)))
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                       + chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))
PY
cp -r run_two run_jump
awk -F, 'NR == 1 { print; next } { printf "%s,%.4f\n", $1, $2 + (NR > 8 ? 1000 : 0) }' \
  run_two/odometry.csv >run_jump/odometry.csv
# Session 27 (sixth probe).
json_with m/module.json m/matrix_nul.json 'pattern.matrix="pattern.png\u0000.txt"'
json_with m/module.json m/along_axis.json 'projector_from_camera.translation_mm=[0,0,-77]' \
  'projector_from_camera.rotation=[0,1,0,-1,0,0,0,0,1]'
mkdir -p m_dir/module.json
mkdir -p same && cp frame8/pattern.png same/depth.png
cp frame8/pattern.png in5.png
mkdir -p cm_p
python3 - <<'PY'
import random, struct
random.seed(1)
# A flat, slightly noisy cloud: no curvature for a cylinder to measure.
pts = [(random.uniform(-40, 40), random.uniform(-30, 30), 120 + random.gauss(0, 0.05)) for _ in range(400)]
with open("flat.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n" % len(pts))
    f.writelines("%.4f %.4f %.4f\n" % p for p in pts)
# A TIFF whose strips reach past the end of the file: OpenCV's decoder fails inside and writes
# to std::cerr.
w = h = 64; rps = 8; n = h // rps
data = bytes([100]) * (w * rps * 2)
ifd_off = 8 + len(data); arr = ifd_off + 2 + 10 * 12 + 4
tags = [(256, 3, 1, w), (257, 3, 1, h), (258, 3, 1, 8), (259, 3, 1, 1), (262, 3, 1, 1),
        (273, 4, n, arr), (277, 3, 1, 1), (278, 3, 1, rps), (279, 4, n, arr + 4 * n), (284, 3, 1, 1)]
ifd = struct.pack("<H", len(tags))
for tag, kind, count, value in tags:
    ifd += struct.pack("<HHIHH", tag, kind, count, value, 0) if kind == 3 else struct.pack("<HHII", tag, kind, count, value)
ifd += struct.pack("<I", 0)
offsets = [8 + i * w * rps for i in range(n)]
open("strips_short.tiff", "wb").write(b"II*\0" + struct.pack("<I", ifd_off) + data + ifd
                                      + struct.pack("<%dI" % n, *offsets) + struct.pack("<%dI" % n, *[w * rps] * n))
PY
cp -r run_ok run_nul
python3 -c "p = 'run_nul/acquisitions.csv'; t = open(p, 'rb').read(); open(p, 'wb').write(t[:120] + b'\0' + t[120:])"
cp -r run_two run_loop
rm run_loop/images/m0/000000_pattern.png && ln -s 000000_pattern.png run_loop/images/m0/000000_pattern.png
cp -r run_two run_blank
white_png run_blank/images/m0/000000_pattern.png
broken_run matrix_missing rig.json 'modules.0.module.pattern.matrix="nothing.png"'
broken_run clock_pose rig.json 'modules.1.clock_h=12'
# Probe 23: run.json's colour filter against colour images; odometry of one reading.
broken_run filter_rggb run.json 'color_filter="RGGB"'
mkdir -p ws_evaluation_cut/evaluation/model && printf '{"all": ' >ws_evaluation_cut/evaluation/model/evaluation.json
cp -r run_two run_period_tiny
json_with run_two/run.json run_period_tiny/run.json 'acquisition_period_s=1e-9'
cp -r run_two run_exposure_s
python3 -c "p = 'run_exposure_s/acquisitions.csv'; L = open(p).read().splitlines(); \
open(p, 'w').write('\n'.join([L[0]] + [l.replace(',2.000,', ',0.002,') for l in L[1:]]) + '\n')"
cp -r run_ok run_same_place
python3 -c "import json; p = 'run_same_place/rig.json'; r = json.load(open(p)); \
r['modules'][1]['carrier_from_camera']['translation_mm'] = r['modules'][0]['carrier_from_camera']['translation_mm']; \
json.dump(r, open(p, 'w'))"
"$S" rgbd run_two --out ws_rec --quiet >/dev/null 2>&1
cp -r ws_rec ws_opt && python3 -c "import json; p = 'ws_opt/workspace.json'; w = json.load(open(p)); \
w['stages']['rgbd']['options'] = {}; json.dump(w, open(p, 'w'))"
cp -r ws_rec ws_stale && python3 -c "import json; p = 'ws_stale/workspace.json'; w = json.load(open(p)); \
w['stages']['model'] = dict(w['stages']['rgbd'], done=False); json.dump(w, open(p, 'w'))"
mkdir -p ws_stale/model && echo '{}' >ws_stale/model/model.json
python3 -c "
with open('chain_big.g2o', 'w') as f:
    f.writelines('VERTEX_SE3:QUAT %d %d 0 0 0 0 0 1\n' % (i, i) for i in range(10001))
    f.writelines('EDGE_SE3:QUAT %d %d 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n' % (i, i + 1) for i in range(10000))
    f.write('FIX 0\n')"
# Session 27 (seventh probe).
json_with m/module.json m/cam_tiny.json 'camera.width=8' 'camera.height=6' 'camera.fx=5' \
  'camera.fy=5' 'camera.cx=4' 'camera.cy=3'
# Session 28 (probe 8 leftovers).
{
  echo 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1'
  echo 'VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1'
  echo 'VERTEX_SE3:QUAT 2 1000000 0 0 0 0 0 1'
  for e in '0 1' '1 2'; do
    echo "EDGE_SE3:QUAT $e 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1"
  done
  echo 'FIX 0'
  echo 'FIX 2'
} >fixed_apart.g2o
python3 -c "
import math
pts = [(0.15 * math.sin(a / 100), y / 1000, 0.15 * math.cos(a / 100)) for a in range(-40, 41) for y in range(-30, 31, 3)]
with open('metres.ply', 'w') as f:
    f.write('ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nend_header\n' % len(pts))
    f.writelines('%g %g %g\n' % p for p in pts)"
# Session 29 (probe 10 leftovers): a square whose start is far from what its edges say, so one
# iteration does not converge.
{
  echo 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1'
  echo 'VERTEX_SE3:QUAT 1 3 0.5 0 0 0 0 1'
  echo 'VERTEX_SE3:QUAT 2 2 4 0 0 0 0.3 0.954'
  echo 'VERTEX_SE3:QUAT 3 -1 2 0 0 0 0 1'
  for e in '0 1 1 0' '1 2 0 1' '2 3 -1 0' '3 0 0 -1'; do
    set -- $e
    echo "EDGE_SE3:QUAT $1 $2 $3 $4 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1"
  done
  echo 'FIX 0'
} >square_far.g2o
python3 -c "import json; s = json.load(open('scenario_two.json')); s['module'] = 'm/module.json'; \
json.dump(s, open('module_and_width.json', 'w'))"
# Session 34 (probe 20): a straight chain of 12 poses 1 m apart with its edges i→i+1 and
# i→i+2 measured exactly (information 1/mm², 1/rad²), as a registration writes it.
python3 -c "
edge = 'EDGE_SE3:QUAT %d %d %g 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n'
with open('chain_loop.g2o', 'w') as f:
    f.writelines('VERTEX_SE3:QUAT %d %d 0 0 0 0 0 1\n' % (i, 1000 * i) for i in range(12))
    f.writelines(edge % (i, i + k, 1000 * k) for k in (1, 2) for i in range(12 - k))
    f.write('FIX 0\n')"
# Session 40: a scene feature placed by the scenario's clock_h or a misspelt member; a scene of
# 1000 bumps (rendered in seconds: a bump ends 8 sigma from its centre).
json_with fpw/scene.json scene_feature_clock_h.json 'scene.features=[{"type": "bump", "station_mm": 0, "clock_h": 2, "height_mm": 2, "radius_mm": 4}]'
json_with fpw/scene.json scene_feature_typo.json 'scene.features=[{"type": "bump", "station_mm": 0, "height_mm": 2, "radius_sigma": 4}]'
python3 -c "
import json, random
random.seed(1)
bump = lambda: {'type': 'bump', 'station_mm': random.uniform(-60, 60),
                'clock_deg': random.uniform(-180, 180), 'height_mm': random.uniform(0.5, 3),
                'radius_mm': random.uniform(1, 6)}
json.dump({'type': 'pipe_wall', 'features': [bump() for _ in range(1000)]},
          open('scene_bumps_1000.json', 'w'))"
# Session 40 (probe 25): an empty module name; a dark or blown-out render; a module whose
# projector sits on the other side or is turned away; pattern images all black; a truth cut short.
broken_run name_empty rig.json 'modules.1.name=""'
scenario_with scenario_ambient_5.json 'render={"ambient_level": 5}'
scenario_with scenario_pattern_level_0.json 'render={"pattern_level": 0}'
module_with m/projector_flipped.json 'projector_from_camera.translation_mm=[77.58527530676709,0,0]'
module_with m/projector_rot180.json 'projector_from_camera.rotation=[-1,0,0,0,-1,0,0,0,1]'
cp -r run_two run_black
python3 -c "
import glob, struct, zlib
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
for f in glob.glob('run_black/images/*/*_pattern.png'):
    w, h = struct.unpack('>II', open(f, 'rb').read()[16:24])
    raw = zlib.compress(b''.join(b'\x00' * (1 + w) for _ in range(h)))
    open(f, 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0))
                        + chunk(b'IDAT', raw) + chunk(b'IEND', b''))"
cp -r run_albedo run_truth_short
"$S" rgbd run_truth_short --out ws_truth_short --quiet >/dev/null 2>&1
sed -i '$d' run_truth_short/truth/poses.csv
mkdir -p above && cp -r run_ok above/run
cp -r run_ok run_odo_micro
python3 -c "
import csv
rows = list(csv.reader(open('run_ok/odometry.csv')))
out = [rows[0]] + [[r[0], repr(float(r[1]) * 1000.0)] + r[2:] for r in rows[1:]]
csv.writer(open('run_odo_micro/odometry.csv', 'w'), lineterminator='\n').writerows(out)"
