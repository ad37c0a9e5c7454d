#!/usr/bin/env python3
"""Independent check of a capture run folder, written from docs/formats.md alone.

Reads the run through the documented files only (standard library, no sewer3d code) and
checks that frames, timestamps, poses, odometry and the feature list are consistent.
Usage: check_run.py RUN_FOLDER. Prints what it checked; exits 1 on the first problem.
"""
import csv
import json
import math
import os
import struct
import sys

KINDS = ("texture_before", "pattern", "texture_after")


def fail(message):
    print("check_run: FAIL: " + message)
    sys.exit(1)


def png_header(path):
    """(width, height, bit depth, colour type) from a PNG's IHDR chunk."""
    with open(path, "rb") as f:
        head = f.read(33)
    if len(head) < 33 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        fail(f"{path}: not a PNG")
    width, height, depth, colour = struct.unpack(">IIBB", head[16:26])
    return width, height, depth, colour


def read_csv(path, header):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or rows[0] != header.split(","):
        fail(f"{path}: header is not '{header}'")
    return rows[1:]


def main(run):
    meta = json.load(open(os.path.join(run, "run.json")))
    if meta.get("format") != "sewer3d-run" or not meta.get("complete"):
        fail("run.json: not a complete sewer3d-run")
    rig = json.load(open(os.path.join(run, meta["rig"])))
    scenario = json.load(open(os.path.join(run, "truth", "scenario.json")))
    modules = rig["modules"]
    if len(modules) != meta["modules"]:
        fail("rig.json and run.json disagree on the number of modules")
    for m in modules:
        r = m["carrier_from_camera"]["rotation"]
        for i in range(3):
            for j in range(3):
                dot = sum(r[3 * k + i] * r[3 * k + j] for k in range(3))
                if abs(dot - (1.0 if i == j else 0.0)) > 1e-6:
                    fail(f"rig.json: module {m['name']} rotation not orthonormal")
        t = m["carrier_from_camera"]["translation_mm"]
        if math.hypot(t[0], t[1]) > 1e-6 or abs(t[2]) > rig["carrier"]["length_mm"] / 2:
            fail(f"rig.json: module {m['name']} camera not on the carrier axis inside the carrier")

    # Index: every image exists with the module's size; triplets complete and timed as documented.
    index = read_csv(os.path.join(run, meta["index"]), "module,counter,image,time_s,exposure_ms,file")
    if len(index) != meta["images"] or meta["images"] != 3 * meta["modules"] * meta["acquisitions"]:
        fail("acquisitions.csv: wrong number of images")
    capture = scenario["capture"]
    period = meta["acquisition_period_s"]
    triplets = {}
    last_time = -1.0
    for module, counter, image, time_s, exposure, file in index:
        module, counter, t = int(module), int(counter), float(time_s)
        if t < last_time:
            fail("acquisitions.csv: rows not sorted by time")
        last_time = t
        if image not in KINDS:
            fail(f"acquisitions.csv: unknown image kind {image}")
        cam = modules[module]["module"]["camera"]
        w, h, depth, colour = png_header(os.path.join(run, file))
        if (w, h) != (cam["width"], cam["height"]):
            fail(f"{file}: {w}x{h}, module camera is {cam['width']}x{cam['height']}")
        if colour != (0 if image == "pattern" else 2):
            fail(f"{file}: colour type {colour} for a {image} image")
        start = counter * period + (module % 2) * capture["group_delay_ms"] * 1e-3
        expected = start + KINDS.index(image) * capture["triplet_interval_ms"] * 1e-3
        if abs(t - expected) > 2e-6:
            fail(f"{file}: time {t} s, expected {expected:.6f} s")
        if abs(float(exposure) - capture["exposure_ms"]) > 1e-3:
            fail(f"{file}: exposure {exposure} ms")
        triplets.setdefault((module, counter), set()).add(image)
    for (module, counter), kinds in triplets.items():
        if kinds != set(KINDS):
            fail(f"module {module} acquisition {counter}: incomplete triplet {sorted(kinds)}")
    for module in range(len(modules)):
        counters = sorted(c for (m, c) in triplets if m == module)
        if counters != list(range(meta["acquisitions"])):
            fail(f"module {module}: counters {counters[:5]}... not 0..{meta['acquisitions'] - 1}")

    # Poses: one per image, same order; unit quaternions; motion as configured.
    poses = read_csv(os.path.join(run, "truth", "poses.csv"),
                     "module,counter,image,time_s,station_mm,x_mm,y_mm,z_mm,qx,qy,qz,qw")
    if len(poses) != len(index):
        fail("truth/poses.csv: not one pose per image")
    motion = scenario["motion"]
    by_time = {}
    for row, pose in zip(index, poses):
        if pose[:3] != row[:3] or abs(float(pose[3]) - float(row[3])) > 1e-9:
            fail(f"truth/poses.csv: row for {row[5]} does not match the index")
        q = [float(x) for x in pose[8:12]]
        if abs(math.sqrt(sum(x * x for x in q)) - 1.0) > 1e-9:
            fail(f"truth/poses.csv: quaternion of {row[5]} not unit")
        by_time[float(pose[3])] = float(pose[4])
    times = sorted(by_time)
    v, dv = motion["speed_mm_s"], motion["speed_variation"]
    if abs(by_time[times[0]] - (motion["start_station_mm"] + v * times[0])) > v * dv * 2.3 / math.pi + 1e-6:
        fail("truth/poses.csv: first station far from the configured start")
    for a, b in zip(times, times[1:]):
        speed = (by_time[b] - by_time[a]) / (b - a)
        if not v * (1 - dv) - 1e-3 <= speed <= v * (1 + dv) + 1e-3:
            fail(f"truth/poses.csv: speed {speed:.2f} mm/s between {a} and {b} s")

    # Odometry: the reported distance is the truth plus exactly the documented error terms.
    reported = read_csv(os.path.join(run, meta["odometry"]), "time_s,distance_mm")
    truth = read_csv(os.path.join(run, "truth", "odometry.csv"),
                     "time_s,true_mm,scale_mm,slip_mm,noise_mm,measured_mm")
    if len(reported) != len(truth) or len(truth) < 2:
        fail("odometry.csv and truth/odometry.csv differ in length")
    odo = scenario["odometry"]
    noise = []
    for (t, d), row in zip(reported, truth):
        t0, true_mm, scale, slip, n, measured = (float(x) for x in row)
        if abs(float(t) - t0) > 1e-9 or abs(float(d) - measured) > 1e-9:
            fail(f"odometry.csv at {t} s differs from the truth's measured value")
        if abs(measured - (true_mm + scale + slip + n)) > 5e-4:
            fail(f"truth/odometry.csv at {t} s: terms do not add up")
        if abs(scale - odo["scale_error"] * true_mm) > 2e-4:
            fail(f"truth/odometry.csv at {t} s: scale term is not scale_error x true")
        station = motion["start_station_mm"] + true_mm
        loss = sum(s["fraction"] * max(0.0, min(station, s["station_mm"] + s["length_mm"]) -
                                       max(motion["start_station_mm"], s["station_mm"]))
                   for s in odo["slips"])
        if abs(slip + loss) > 2e-4:
            fail(f"truth/odometry.csv at {t} s: slip {slip} mm, the configured stretches give {-loss:.4f}")
        noise.append(n)
    if max(abs(n) for n in noise) > 6 * odo["noise_mm"] + 1e-4:
        fail("truth/odometry.csv: noise beyond 6 sigma")

    # Features: ids unique, every joint and feature of the world listed at its station.
    world = json.load(open(os.path.join(run, "truth", "world.json")))
    features = json.load(open(os.path.join(run, "truth", "features.json")))["features"]
    ids = [f["id"] for f in features]
    if len(set(ids)) != len(ids):
        fail("truth/features.json: duplicate ids")
    listed = {f["id"]: f for f in features}
    starts = [0.0]
    for s in world["sections"]:
        starts.append(starts[-1] + s["length_mm"])
    for i, joint in enumerate(world["joints"]):
        f = listed.get(joint["id"])
        if f is None or f["code"] != "BAJ" or abs(f["station_mm"] - starts[i + 1]) > 1e-6:
            fail(f"truth/features.json: joint {joint['id']} missing or not at station {starts[i + 1]}")
    for wf in world["features"]:
        f = listed.get(wf["id"])
        if f is None or f["type"] != wf["type"] or abs(f["station_mm"] - wf["station_mm"]) > 1e-6:
            fail(f"truth/features.json: feature {wf['id']} missing or moved")
    for f in features:
        if not 0.0 < f["clock_h"] <= 12.0 or not -1e-6 <= f["station_mm"] <= starts[-1]:
            fail(f"truth/features.json: {f['id']} at clock {f['clock_h']} h, station {f['station_mm']} mm")

    print(f"check_run: OK: {len(index)} images of {len(modules)} modules, {meta['acquisitions']} acquisitions, "
          f"{len(truth)} odometry samples, {len(features)} features")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    main(sys.argv[1])
