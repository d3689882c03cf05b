#!/usr/bin/env python3
"""Writes the seed corpora in fuzz/corpus/<harness>/ (run once; the files are kept in the repo).

Numbers use the encoding of fuzz/fuzz_input.hpp: a tag byte < 0x80 and a signed byte k for
k * 2^-(tag % 8), or the tag 0x80 and a little-endian binary64."""
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def small(k, shift=0):
    return bytes([shift % 8, k & 0xFF])


def raw(x):
    return b"\x80" + struct.pack("<d", x)


def num(x):
    # Small dyadic values compactly, everything else as binary64.
    for shift in range(8):
        k = x * (1 << shift)
        if k == int(k) and -128 <= k <= 127:
            return small(int(k), shift)
    return raw(x)


def vec(*v):
    return b"".join(num(x) for x in v)


def write(harness, name, data):
    d = os.path.join(HERE, "corpus", harness)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


CYL = vec(0, 0, 0) + vec(0, 0, 2) + num(5)  # axis z, z in [0, 2], radius 5
ELL = vec(0, 0, 0) + vec(5, 0, 0) + vec(0, 5, 0) + vec(0, 0, 2)
lines = {
    "tangent": (vec(3, 4, 1), vec(-4, 3, 0)),
    "on_wall": (vec(3, 4, 1), vec(0, 0, 1)),
    "graze_rim": (vec(3, 4, 2), vec(3, 4, -5)),
    "cap_chord": (vec(-7, 1, 2), vec(1, 0, 0)),
    "through": (vec(-9, 0, 1), vec(1, 0, 0)),
    "miss": (vec(6, 0, 1), vec(0, 1, 0)),
    "axis": (vec(0, 0, -1), vec(0, 0, 1)),
    "near_tangent": (vec(3, 4 + 2**-40, 1), vec(-4, 3, 0)),
    "huge": (vec(1e300, 0, 1), vec(-1e300, 1e-300, 0)),
    "subnormal": (vec(5e-324, 5, 1), vec(1, 0, 0)),
}
for name, (o, d) in lines.items():
    for sel, kind in ((0, "line"), (1, "ray"), (2, "segment"), (3, "line_ell"), (5, "segment_ell")):
        solid = ELL if sel >= 3 else CYL
        write("fuzz_line_cylinder", f"{name}_{kind}", bytes([sel]) + o + d + solid)

tris = {
    "vertex_on_wall": vec(3, 4, 1) + vec(9, 12, 2) + vec(9, 12, 0),
    "edge_tangent": vec(7, -1, 1) + vec(-1, 5, 1) + vec(6, 8, 1),
    "in_cap_plane": vec(-1, 0, 2) + vec(1, 1, 2) + vec(0, -2, 2),
    "vertex_on_rim": vec(3, 4, 2) + vec(6, 8, 3) + vec(6, 8, 4),
    "crossing": vec(-9, 0, 1) + vec(9, 1, 1) + vec(9, -1, 1),
    "separated": vec(6, 0, 1) + vec(7, 1, 1) + vec(7, -1, 1),
    "segment": vec(3, 4, 1) + vec(3, 4, 1) + vec(6, 8, 1),
    "point": vec(3, 4, 1) + vec(3, 4, 1) + vec(3, 4, 1),
    "axis_plane": vec(0, 0, -1) + vec(0, 0, 3) + vec(8, 0, 1),
    "tiny": vec(1e-300, 0, 1) + vec(0, 1e-300, 1) + vec(0, 0, 1 + 2**-52),
}
for name, t in tris.items():
    write("fuzz_triangle_cylinder", name, t + CYL)

A = vec(0, 0, 0) + vec(0, 0, 2) + num(1)
pairs = {
    "cap_cap": vec(0.5, 0, 2) + vec(0.5, 0, 5) + num(1),
    "cap_wall": vec(-1, 0, 3) + vec(1, 0, 3) + num(1),
    "wall_wall_crossing": vec(2, -1, 1) + vec(2, 1, 1) + num(1),
    "wall_wall_parallel": vec(2, 0, 1) + vec(2, 0, 3) + num(1),
    "rim_cap": vec(1, 0.5, 2) + vec(2.25, 0.5, 3.625) + num(1),
    "rim_wall": vec(0.625, -1.25, 3.5) + vec(2.625, 1.25, 2) + num(1),
    "separated": vec(3, -1, 1) + vec(3, 1, 1) + num(1),
    "overlapping": vec(1, -1, 1) + vec(1, 1, 1) + num(1),
    "coaxial": vec(0, 0, 1) + vec(0, 0, 3) + num(0.5),
    "same_midpoint": vec(-1, 0, 1) + vec(1, 0, 1) + num(0.25),
    "huge": vec(1e200, 0, 0) + vec(1e200, 1, 0) + num(1e100),
}
for name, b in pairs.items():
    write("fuzz_cylinder_cylinder", name, A + b)

# Rims dipping into the other cylinder far below an ulp (tests/test_cylinder_wide_range.cpp).
h = float.fromhex
R = h("0x1.38p-2")
full_pairs = {
    "needles_cap_on_wall": vec(0, 0, 0) + vec(0, 2.0**422, 0) + num(22.5)
    + vec(2.0**422, 8.75, 22.5) + vec(22.5, 22.5, 22.5) + num(22.5),
    "rim_line_quarter": vec(0, 0, 99) + vec(2, h("-0x1.01414fb0000fap+401"), h("0x1.72727275a27d5p-397")) + num(R)
    + vec(R, 0, h("0x1.00002p+417")) + vec(-0.25, R, R) + num(R),
}
for name, ab in full_pairs.items():
    write("fuzz_cylinder_cylinder", name, ab)

cyl = {"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 5}
queries = {
    "point": {"id": 1, "query": "point_cylinder", "point": [3, 4, 1], "cylinder": cyl},
    "line": {"id": 2, "query": "line_cylinder", "line": {"origin": [3, 4, 1], "direction": [-4, 3, 0]}, "cylinder": cyl},
    "ray": {"id": "r", "query": "ray_cylinder", "ray": {"origin": [0, 0, 1], "direction": [1, 0, 0]}, "cylinder": cyl},
    "segment": {"id": 3, "query": "segment_cylinder", "segment": {"p0": ["1/3", 0, 1], "p1": [9, 0, 1]}, "cylinder": cyl},
    "elliptic": {"id": 4, "query": "line_elliptic_cylinder", "line": {"origin": [0, 0, 0.5], "direction": [1, 0, 0]},
                 "elliptic_cylinder": {"base": [0, 0, 0], "a": [2, 0, 0], "b": [0, 1, 0], "c": [0, 0, 1]}},
    "triangle": {"id": 5, "query": "triangle_cylinder", "triangle": [[3, 4, 1], [9, 12, 2], [9, 12, 0]], "cylinder": cyl},
    "cylinders": {"id": 6, "query": "cylinder_cylinder", "a": {"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1},
                  "b": {"center": [2, 0, 1], "axis": [0, 1, 0], "radius": 1, "height": 2}},
    "hexfloat": {"id": 7, "query": "point_cylinder", "point": ["0x1.8p-3", "0x0.0000000000001p-1022", 1], "cylinder": cyl},
    "huge_string": {"id": 8, "query": "point_cylinder", "point": ["1e400", 0, 1], "cylinder": cyl},
}
for name, q in queries.items():
    write("fuzz_json_line", name, json.dumps(q).encode())
for name, text in {
    "truncated": b'{"id": 9, "query": "point_cylinder", "point": [3, 4',
    "not_object": b"[1, 2, 3]",
    "nested": b"[" * 200 + b"]" * 200,
    "binary": bytes(range(256)),
    "bad_number": b'{"id": 10, "query": "point_cylinder", "point": ["abc", 0, 1], "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 5}}',
    "overflow": b'{"id": 11, "query": "point_cylinder", "point": [1e999, 0, 1], "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 5}}',
}.items():
    write("fuzz_json_line", name, text)
