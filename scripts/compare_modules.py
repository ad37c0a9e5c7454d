#!/usr/bin/env python3
"""Recovered-vs-true table (markdown) of two module files: python3 compare_modules.py TRUE CALIBRATED."""
import json
import math
import sys


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def baseline(m):
    # |t| of projector_from_camera: the distance between the two centres.
    return math.sqrt(sum(v * v for v in m["projector_from_camera"]["translation_mm"]))


def rotation_angle_deg(a, b):
    ra, rb = a["projector_from_camera"]["rotation"], b["projector_from_camera"]["rotation"]
    # trace(Ra^T Rb) for row-major 3x3 matrices
    trace = sum(ra[3 * i + k] * rb[3 * i + k] for i in range(3) for k in range(3))
    return math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0))))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: compare_modules.py TRUE_MODULE CALIBRATED_MODULE")
    true, cal = load(sys.argv[1]), load(sys.argv[2])
    print("| parameter | true | calibrated | error |")
    print("|---|---|---|---|")
    for device in ("camera", "projector"):
        t, c = true[device], cal[device]
        for key in ("fx", "fy"):
            err = 100.0 * (c[key] - t[key]) / t[key]
            print(f"| {device} {key} (px) | {t[key]:.3f} | {c[key]:.3f} | {err:+.4f} % |")
        for key in ("cx", "cy"):
            print(f"| {device} {key} (px) | {t[key]:.3f} | {c[key]:.3f} | {c[key] - t[key]:+.3f} px |")
        print(f"| {device} k1, k2 | {t['k'][0]:.4f}, {t['k'][1]:.4f} | {c['k'][0]:.4f}, {c['k'][1]:.4f} | |")
    bt, bc = baseline(true), baseline(cal)
    print(f"| baseline (mm) | {bt:.3f} | {bc:.3f} | {bc - bt:+.3f} mm |")
    print(f"| projector_from_camera rotation | | | {rotation_angle_deg(true, cal):.4f}° |")


if __name__ == "__main__":
    main()
