#!/usr/bin/env python3
"""line_double.py -- a line, ray and segment test against a cylinder in double arithmetic, as a
program judged by `certcyl judge --exec`.

certcyl writes `certcyl query` lines on the program's standard input, one case per line, e.g.

    {"id": "ray_cylinder/rim/0", "query": "ray_cylinder",
     "ray": {"origin": [x, y, z], "direction": [x, y, z]},
     "cylinder": {"p0": [x, y, z], "p1": [x, y, z], "radius": r}}

(a line has "line", a segment "segment" with "p0" and "p1") and reads one answer line back per
input line, in the same order: {"id": <the line's id>, "answer": "separated" | "touching" |
"overlapping" | "intersecting" | "undecided"}, or {"id": ..., "error": "..."} for an error of the
method. The test is the textbook one: the parameter range is clipped to the slab between the cap
planes, then to the roots of the tube quadratic; touching when one point is left. Near tangency
the discriminant cancels and its rounding decides the answer, which is what certcyl finds.

Run it by hand on a cases file:   certcyl cases --query ray_cylinder --size tiny | python3 line_double.py
Judge it:                         certcyl judge --exec "python3 line_double.py" --query ray_cylinder --size small
"""
import json
import math
import sys


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def clip(o, d, cyl, lo, hi):
    """The points o + t d, t in [lo, hi], against the cylinder."""
    p0, p1, r = cyl["p0"], cyl["p1"], cyl["radius"]
    A, w = sub(p1, p0), sub(o, p0)
    AA, dA, wA = dot(A, A), dot(d, A), dot(w, A)
    # The slab 0 <= (w + t d).A <= A.A.
    if dA == 0:
        if wA < 0 or wA > AA:
            return "separated"
    else:
        t0, t1 = sorted((-wA / dA, (AA - wA) / dA))
        lo, hi = max(lo, t0), min(hi, t1)
    # The tube: a t^2 + b t + c <= 0.
    a = dot(d, d) * AA - dA * dA
    b = 2 * (dot(w, d) * AA - wA * dA)
    c = dot(w, w) * AA - wA * wA - r * r * AA
    if a == 0:
        if c > 0:
            return "separated"
    else:
        disc = b * b - 4 * a * c
        if disc < 0:
            return "separated"
        s = math.sqrt(disc)
        lo, hi = max(lo, (-b - s) / (2 * a)), min(hi, (-b + s) / (2 * a))
    if lo > hi:
        return "separated"
    return "touching" if lo == hi else "overlapping"


def answer(q):
    kind, cyl = q["query"], q["cylinder"]
    if kind == "line_cylinder":
        return clip(q["line"]["origin"], q["line"]["direction"], cyl, -math.inf, math.inf)
    if kind == "ray_cylinder":
        return clip(q["ray"]["origin"], q["ray"]["direction"], cyl, 0.0, math.inf)
    if kind == "segment_cylinder":
        s = q["segment"]
        return clip(s["p0"], sub(s["p1"], s["p0"]), cyl, 0.0, 1.0)
    raise ValueError("no test for " + kind)


def main():
    out = sys.stdout
    for line in sys.stdin:
        if not line.strip():
            continue
        q = json.loads(line)
        try:
            reply = {"id": q.get("id"), "answer": answer(q)}
        except (ValueError, KeyError, ZeroDivisionError) as e:
            reply = {"id": q.get("id"), "error": str(e)}
        # One answer per line, flushed at once: a caller that writes a line and waits for its
        # answer is served (certcyl judge also works with buffered output).
        out.write(json.dumps(reply) + "\n")
        out.flush()


if __name__ == "__main__":
    main()
