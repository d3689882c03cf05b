"""Certified cylinder intersection queries on numpy arrays.

Every answer is proved in exact arithmetic on the binary64 values given (certcyl's certified
layer): ``SEPARATED``, ``TOUCHING`` or ``OVERLAPPING`` (cylinder pairs may say ``UNDECIDED``
beyond the configured precision, never a guess). The batch functions take one query per row:

    import numpy as np, certcyl
    cyl = np.array([[0, 0, 0, 0, 0, 2, 1.0]])          # p0, p1, radius
    r = certcyl.line_cylinder([[-2, 1, 1]], [[1, 0, 0]], cyl)
    r.answer   # array([1], dtype=int8): TOUCHING, the line at distance 1 from the axis
    r.t_in, r.t_out, r.gap

Cylinders are N x 7 (p0, p1, radius; ``cylinders_from_center`` converts the seeds' form), points,
origins and directions N x 3, triangles N x 9 or N x 3 x 3, elliptic cylinders N x 12 (base, a,
b, c). One operand may be a single row, broadcast against the others. A wrong shape or dtype is
a ``ValueError`` naming the argument; a row the library rejects (a non-finite number, a radius
that is not positive, a zero direction) is a ``certcyl.InvalidInput`` (a ``ValueError``) naming
the row and the field.

``query`` answers one query exactly as ``certcyl query`` does (numbers may be ``Fraction`` or
strings, read exactly) and returns its full certificate; ``judge`` scores a Python
implementation of a query on the cases of ``certcyl cases``, as ``certcyl judge`` scores a
program.
"""

import json
import math
import os
from fractions import Fraction

import numpy as np

from ._certcyl import (
    INTERSECTING,
    OVERLAPPING,
    SEPARATED,
    TOUCHING,
    UNDECIDED,
    BatchResult,
    InvalidInput,
    cylinder_cylinder,
    line_cylinder,
    line_elliptic_cylinder,
    point_cylinder,
    point_elliptic_cylinder,
    ray_cylinder,
    ray_elliptic_cylinder,
    segment_cylinder,
    segment_elliptic_cylinder,
    triangle_cylinder,
)
from . import _certcyl

__all__ = [
    "SEPARATED", "TOUCHING", "OVERLAPPING", "INTERSECTING", "UNDECIDED", "BatchResult", "InvalidInput",
    "line_cylinder", "ray_cylinder", "segment_cylinder", "line_elliptic_cylinder", "ray_elliptic_cylinder",
    "segment_elliptic_cylinder", "point_cylinder", "point_elliptic_cylinder", "triangle_cylinder",
    "cylinder_cylinder", "cylinders_from_center", "query", "QueryResult", "judge", "JudgeResult",
]

# The queries certcyl.judge can judge (those of `certcyl cases`).
JUDGE_QUERIES = ("line_cylinder", "ray_cylinder", "segment_cylinder", "line_elliptic_cylinder", "triangle_cylinder",
                 "cylinder_cylinder")


def cylinders_from_center(centers, axes, radii, heights):
    """The N x 7 cylinders (p0, p1, radius) of the seeds' form: center C, axis W, radius r, height h.

    p0 = C - (h/2) W and p1 = C + (h/2) W, computed in float64 (so rounded, unlike
    ``certcyl query``'s exact conversion of the same form; W is not renormalised). Each argument
    is N rows or a single row (radii and heights: N values or one). Raises ValueError on shapes
    that do not broadcast.
    """
    c = np.atleast_2d(np.asarray(centers, dtype=np.float64))
    w = np.atleast_2d(np.asarray(axes, dtype=np.float64))
    r = np.atleast_1d(np.asarray(radii, dtype=np.float64))
    h = np.atleast_1d(np.asarray(heights, dtype=np.float64))
    for name, a, width in (("centers", c, 3), ("axes", w, 3)):
        if a.ndim != 2 or a.shape[1] != width:
            raise ValueError(f"cylinders_from_center: {name}: expected shape (N, 3) or (3,), got {a.shape}")
    for name, a in (("radii", r), ("heights", h)):
        if a.ndim != 1:
            raise ValueError(f"cylinders_from_center: {name}: expected shape (N,) or a number, got {a.shape}")
    try:
        n = np.broadcast_shapes((c.shape[0],), (w.shape[0],), r.shape, h.shape)[0]
    except ValueError:
        raise ValueError(f"cylinders_from_center: rows differ: centers {c.shape[0]}, axes {w.shape[0]}, "
                         f"radii {r.shape[0]}, heights {h.shape[0]} (each N or one)") from None
    half = (h / 2)[:, None] * w
    out = np.empty((n, 7))
    out[:, 0:3] = c - half
    out[:, 3:6] = c + half
    out[:, 6] = r
    return out


def _number(x, where):
    """A JSON value `certcyl query` reads exactly: floats and ints as numbers, Fractions as "p/q"."""
    if isinstance(x, bool):
        raise ValueError(f"query: {where}: expected a number, got {x!r}")
    if isinstance(x, Fraction):
        return f"{x.numerator}/{x.denominator}"
    if isinstance(x, str):
        return x
    if isinstance(x, (int, np.integer)):
        return str(int(x)) if abs(int(x)) > 2**53 else int(x)
    if isinstance(x, (float, np.floating)):
        if not math.isfinite(float(x)):
            raise ValueError(f"query: {where}: not a finite number: {x!r}")
        return float(x)
    raise ValueError(f"query: {where}: expected a number (int, float, Fraction or a string), got {type(x).__name__}")


def _operand(value, where):
    if isinstance(value, dict):
        return {k: _operand(v, f"{where}.{k}") for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_operand(v, f"{where}[{i}]") for i, v in enumerate(value)]
    return _number(value, where)


def _exact(value):
    """Certificate strings that spell a rational as Fraction; other values unchanged."""
    if isinstance(value, dict):
        return {k: _exact(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_exact(v) for v in value]
    if isinstance(value, str):
        try:
            return Fraction(value)
        except ValueError:
            return value
    return value


class QueryResult:
    """One query's full answer, as `certcyl query` writes it.

    answer: "separated", "touching", "overlapping" or "undecided" (a floating method may say
    "invalid"); code: the answer's code (SEPARATED ...; None for "invalid"); certified: True when
    the answer is proved; method, nt: the method and the number type or stage that decided;
    certificate: the certificate, exact rationals as Fraction (other exact values, such as
    "a + b*sqrt(c)", as strings); interval: for line, ray and segment queries, the ends of the
    parameter interval; gap: the certified signed gap [lo, hi] of a certified answer (log(phi*)
    for cylinder pairs, the depth margin of the other queries); gap_quantity: its name,
    "log_phi" or "depth_margin" (None without a gap); line: the whole answer line as a dict.
    """

    _codes = {"separated": SEPARATED, "touching": TOUCHING, "overlapping": OVERLAPPING, "undecided": UNDECIDED}

    def __init__(self, line):
        self.line = line
        self.answer = line["answer"]
        self.code = self._codes.get(self.answer)
        self.certified = line.get("certified", False)
        self.method = line.get("method")
        self.nt = line.get("nt")
        self.certificate = _exact(line.get("certificate"))
        self.interval = _exact(line.get("interval"))
        self.gap = line.get("gap")
        self.gap_quantity = line.get("gap_quantity")

    def __repr__(self):
        proved = "certified" if self.certified else "not certified"
        text = f"<certcyl.QueryResult {self.answer} ({proved}, {self.method}/{self.nt})"
        if self.certificate:
            text += f" certificate={self.certificate!r}"
        if self.interval is not None:
            text += f" interval={self.interval!r}"
        return text + ">"


def query(query, method="certified", nt=None, **operands):
    """Answers one query exactly as ``certcyl query --method METHOD [--nt NT]`` answers its line.

    query: the query's name ("point_cylinder", "line_cylinder", ..., the table of the README);
    operands: its JSON members as keyword arguments, e.g.
    ``certcyl.query("point_cylinder", point=["3/5", Fraction(4, 5), 1],
    cylinder={"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1})``. Numbers may be int, float,
    Fraction or strings ("p/q", "0.1", hexfloats), each read exactly. Returns a QueryResult.
    Raises ValueError naming the field for a line `certcyl query` would reject.
    """
    line = {"query": query}
    for name, value in operands.items():
        line[name] = _operand(value, name)
    answer = json.loads(_certcyl._answer_line(json.dumps(line), method, nt or ""))
    if "error" in answer:
        raise ValueError(f"query: {answer['error']}")
    return QueryResult(answer)


class JudgeResult:
    """The outcome of ``certcyl.judge``: summary (the table ``certcyl judge`` prints), folder
    (the results folder: families.csv, counterexamples.jsonl, answers.jsonl, summary.txt and
    index.html, the one-page report) and families (families.csv's rows as dicts, numbers as int
    or float)."""

    def __init__(self, summary, folder):
        import csv
        self.summary = summary
        self.folder = folder
        self.families = []
        with open(os.path.join(folder, "families.csv"), newline="") as f:
            for row in csv.DictReader(f):
                for k, v in row.items():
                    if k in ("method", "query", "family") or v == "":
                        continue
                    row[k] = float(v) if k.startswith(("failure_rate", "t_error_")) else int(v)
                self.families.append(row)

    def family(self, query, family="all"):
        """families.csv's row of one query and family ("all": the query's total)."""
        for row in self.families:
            if row["query"] == query and row["family"] == family:
                return row
        raise KeyError(f"{query}/{family}")

    def __repr__(self):
        return f"<certcyl.JudgeResult {self.folder}>\n{self.summary}"


def judge(function, query="ray_cylinder", size="small", *, vectorized=False, seed=1, families=(), method=None,
          out="results", name="judge", threads=1, map_cells=None, map_step=1, hunt_evaluations=None, contract="solid"):
    """Judges a Python implementation of a query as ``certcyl judge`` judges a program.

    The cases are those of ``certcyl cases --query QUERY --size SIZE --seed SEED [--family F ...]``
    (query one of JUDGE_QUERIES). function is called with each case's operands as float64
    arrays: line and ray queries (origin, direction, cylinder), segment (p0, p1, cylinder),
    line_elliptic_cylinder (origin, direction, the 12 numbers base, a, b, c), triangle (a 3 x 3
    triangle, cylinder), cylinder pairs (a, b); cylinders are (p0, p1, radius). With
    vectorized=True it is called once with every case, N rows per operand, and returns N answers.
    An answer is an answer code (SEPARATED, TOUCHING, OVERLAPPING, INTERSECTING, UNDECIDED; a
    negative code is an error of the method), a bool (True: the sets meet) or a word
    ("separated", ..., "intersecting", "undecided", "invalid", "error"). A line, ray or segment
    query may return (answer, t_in) or (answer, t_in, t_out) (None for none): its entry parameter
    is then scored against the certified one as ``certcyl judge`` scores an answers file's
    interval (families.csv's t_error columns).

    Then, as ``certcyl judge`` does for a plugin or a program, the query's failure maps
    (map_cells x map_cells cells, map_step ulps apart; map_cells None: the size's, 16 tiny, 32
    small, 64 default, 128 large; 0: none) and the hunt for its worst input (hunt_evaluations
    inputs, a quarter for cylinder pairs; None: the size's, 20 tiny, 150 small, 1000 default,
    5000 large; 0: none), with the same calls (every cell in one call when vectorized).

    contract: what a hit promises for ray_cylinder and segment_cylinder, as ``certcyl judge
    --contract`` (src/study/contract.hpp): "solid" (the set meets the solid cylinder),
    "surface_entry" (entering from outside: a ray starting inside is a miss) or "surface_hit" (a
    surface point at t > 0, an exit counting); the answers are judged against the certified
    answer under it.

    Writes OUT/NAME/ (families.csv, counterexamples.jsonl, answers.jsonl, summary.txt, the maps
    in failure_maps/ and failure_maps.csv, hunt.csv, and the one-page report index.html) and
    returns a JudgeResult. An exception raised by the function ends the run: what was answered
    before it is written, and the exception propagates (with a note naming the case).
    """
    if query not in JUDGE_QUERIES:
        raise ValueError(f"judge: query: expected one of {', '.join(JUDGE_QUERIES)}, got {query!r}")
    if not callable(function):
        raise ValueError(f"judge: function: not callable: {function!r}")
    if int(threads) < 0:
        raise ValueError(f"judge: threads: expected 0 (every core) or a positive number of threads, got {threads}")
    def count(value, key, lo, hi):
        if value is None:
            return -1
        if isinstance(value, bool) or int(value) != value or not (value == 0 or lo <= int(value) <= hi):
            raise ValueError(f"judge: {key}: expected 0 (none) or an integer from {lo} to {hi}, got {value!r}")
        return int(value)
    cells = count(map_cells, "map_cells", 2, 1024)
    evaluations = count(hunt_evaluations, "hunt_evaluations", 1, 100_000_000)
    if isinstance(map_step, bool) or int(map_step) != map_step or not 1 <= int(map_step) <= 1_000_000_000:
        raise ValueError(f"judge: map_step: expected an integer from 1 to 10^9, got {map_step!r}")
    if contract not in ("solid", "surface_entry", "surface_hit"):
        raise ValueError(f"judge: contract: expected solid, surface_entry or surface_hit, got {contract!r}")
    if contract != "solid" and query not in ("ray_cylinder", "segment_cylinder"):
        raise ValueError(f"judge: contract {contract}: defined for ray_cylinder and segment_cylinder only, got {query}")
    label = method or getattr(function, "__qualname__", None) or "python"
    summary, folder = _certcyl._judge(function, query, str(size), int(seed), list(families), bool(vectorized), label,
                                      str(out), str(name), int(threads), cells, int(map_step), evaluations, contract)
    return JudgeResult(summary, folder)
