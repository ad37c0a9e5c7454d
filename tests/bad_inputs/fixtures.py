#!/usr/bin/env python3
"""Writes the binary fixtures of the bad-input table into the folder given as argument.

Only the standard library: PNG chunks are assembled by hand (zlib + crc32), PLY files with
struct, so every fixture is exactly the malformed thing its name says.
"""
import os
import math
import random
import struct
import sys
import zlib


def png_chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def png(width, height, bit_depth, rows_data, colour_type=0):
    header = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", header) +
            png_chunk(b"IDAT", rows_data) + png_chunk(b"IEND", b""))


def zero_rows(width, height, bytes_per_px):
    """Compressed filter-0 rows of zeros, streamed so a 20000 x 20000 image costs little."""
    comp = zlib.compressobj(9)
    row = b"\x00" * (1 + width * bytes_per_px)
    out = [comp.compress(row) for _ in range(height)]
    out.append(comp.flush())
    return b"".join(out)


def ply(path, vertex_type, values, count=None, extra_header=""):
    n = len(values) if count is None else count
    fmt = {"char": "b", "short": "h", "int": "i", "uchar": "B", "ushort": "H", "uint": "I",
           "float": "f", "double": "d"}[vertex_type]
    head = ("ply\nformat binary_little_endian 1.0\n"
            f"element vertex {n}\n"
            f"property {vertex_type} x\nproperty {vertex_type} y\nproperty {vertex_type} z\n"
            f"{extra_header}end_header\n")
    with open(path, "wb") as f:
        f.write(head.encode())
        for v in values:
            f.write(struct.pack("<" + fmt * 3, *v))


def ascii_ply(path, points, count):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {count}\n"
                "property float x\nproperty float y\nproperty float z\nend_header\n")
        for p in points:
            f.write(" ".join(str(c) for c in p) + "\n")


def main(out):
    os.makedirs(out, exist_ok=True)
    j = lambda name: os.path.join(out, name)
    # A 20000 x 20000 8-bit pattern matrix, a few hundred kB on disk.
    with open(j("huge_matrix.png"), "wb") as f:
        f.write(png(20000, 20000, 8, zero_rows(20000, 20000, 1)))
    # A 60000 x 60000 header over a few bytes of data.
    with open(j("huge_header.png"), "wb") as f:
        f.write(png(60000, 60000, 8, zlib.compress(b"\x00" * 100)))
    # A 1 x 1 grey image.
    # A 200 x 6 matrix (the default's size) of coin flips: windows unique, spots touching.
    flips = random.Random(7)
    with open(j("coin_spots.png"), "wb") as f:
        f.write(png(200, 6, 8, zlib.compress(b"".join(
            b"\x00" + bytes(255 * flips.randrange(2) for _ in range(200)) for _ in range(6)))))
    with open(j("one_pixel.png"), "wb") as f:
        f.write(png(1, 1, 8, zlib.compress(b"\x00\x80")))
    # Valid chunk CRCs over bad image data: rows short, a row too many, a bad filter type.
    rows = b"".join(b"\x00" + bytes(range(8)) for _ in range(8))
    for name, data in (("short_data", rows[:-9]), ("too_much_data", rows + rows[:9]),
                       ("bad_filter", b"\x07" + rows[1:])):
        with open(j(name + ".png"), "wb") as f:
            f.write(png(8, 8, 8, zlib.compress(data)))
    # Integer-typed coordinates on a 100 mm cylinder patch (x^2 + z^2 = 50^2 about the y axis).
    ring = [(int(round(50 * c)), y, int(round(50 * s)) + 150)
            for y in range(-20, 21, 10)
            for c, s in ((1, 0), (0.6, 0.8), (0, 1), (-0.6, 0.8), (-1, 0), (0.8, 0.6))]
    for t in ("char", "short", "int"):
        pts = ring if t != "char" else [(x, y, z - 100) for x, y, z in ring]
        ply(j(f"coords_{t}.ply"), t, pts)
    # Header says 3 vertices, the body holds 30.
    plane = [(float(x), float(y), 100.0) for x in range(6) for y in range(5)]
    ply(j("count_low.ply"), "float", plane, count=3)
    ascii_ply(j("count_low_ascii.ply"), plane, 3)
    with open(j("nan_ascii.ply"), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                "property float z\nend_header\n1 2 3\nnan 2 3\n")
    # Identical and collinear points.
    ply(j("identical.ply"), "float", [(1.0, 2.0, 100.0)] * 50)
    ply(j("collinear.ply"), "float", [(float(i), 2.0 * i, 100.0 + i) for i in range(50)])
    # A plane behind the camera (z < 0), and an arc of a Ø300 pipe whose axis is the view's z.
    ply(j("behind.ply"), "float", [(x, y, -100.0 - 0.01 * x) for x, y, _ in plane])
    arc = [(150 * math.cos(0.05 * i), 150 * math.sin(0.05 * i), 10.0 + 10 * k)
           for i in range(60) for k in range(10)]
    ply(j("arc_z.ply"), "float", arc)
    # A good cylinder patch with one point at 1e30 (a corrupt value, not a shape).
    ply(j("far_point.ply"), "double", [(float(x), float(y), float(z)) for x, y, z in ring]
        + [(1e30, 0.0, 150.0)])


if __name__ == "__main__":
    main(sys.argv[1])
