"""The Python package: answers known by construction, the same answers and gaps as `certcyl
cases` and `certcyl query` on the study's hard cases, bad input raising clear exceptions, and a
Python implementation judged in process.

    /usr/bin/python3 tests/python/test_certcyl.py CERTCYL_BIN   (with PYTHONPATH=<build>/python)
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest
from fractions import Fraction

import numpy as np

import certcyl

CERTCYL = None  # the command, from the command line

S, T, O = certcyl.SEPARATED, certcyl.TOUCHING, certcyl.OVERLAPPING
CODES = {"separated": S, "touching": T, "overlapping": O, "undecided": certcyl.UNDECIDED}

#   z
#   2 +---+---+       the cylinder: axis from (0,0,0) to (0,0,2), radius 1
#     |   |   |       lines along x at height 1, their distance to the axis y:
#   1 |---|---|--->   y = 0 through the axis, y = 1 on the wall, y = 1 + ulp off it
#     |   |   |
#   0 +---+---+
#    -1   0   1   x
CYLINDER = np.array([0, 0, 0, 0, 0, 2, 1.0])
ABOVE_ONE = np.nextafter(1.0, 2.0)


def command(args, text):
    return subprocess.run([CERTCYL] + args, input=text, capture_output=True, text=True, check=True).stdout


class KnownByConstruction(unittest.TestCase):
    def test_lines_through_on_and_off_the_wall(self):
        origins = np.array([[-3, 0, 1], [-3, 1, 1], [-3, ABOVE_ONE, 1], [-3, -1, 1]], dtype=np.float64)
        r = certcyl.line_cylinder(origins, [1, 0, 0], CYLINDER)  # direction and cylinder broadcast
        self.assertEqual(r.answer.tolist(), [O, T, S, T])
        self.assertEqual(r.answer.dtype, np.int8)
        # Through the axis: enters at x = -1 (t = 2), leaves at x = 1 (t = 4), both exact doubles.
        self.assertEqual((r.t_in[0], r.t_out[0]), (2.0, 4.0))
        # On the wall: the one point x = 0, t = 3.
        self.assertEqual((r.t_in[1], r.t_out[1]), (3.0, 3.0))
        self.assertTrue(math.isnan(r.t_in[2]) and math.isnan(r.t_out[2]))
        # The gap's sign is the answer's: positive overlapping, zero touching, negative separated.
        self.assertEqual(r.gap.shape, (4, 2))
        self.assertGreater(r.gap[0, 0], 0)
        self.assertEqual(r.gap[1].tolist(), [0.0, 0.0])
        self.assertLess(r.gap[2, 1], 0)
        self.assertEqual(len(r), 4)
        self.assertIn("1 overlapping", repr(r))

    def test_rays_and_segments(self):
        # A ray pointing away from the cylinder misses it; towards it, meets it.
        r = certcyl.ray_cylinder([[-3, 0, 1], [-3, 0, 1]], [[-1, 0, 0], [1, 0, 0]], CYLINDER)
        self.assertEqual(r.answer.tolist(), [S, O])
        self.assertEqual((r.t_in[1], r.t_out[1]), (2.0, 4.0))
        # A ray starting inside enters at its origin.
        r = certcyl.ray_cylinder([0, 0, 1], [1, 0, 0], CYLINDER)
        self.assertEqual((r.answer[0], r.t_in[0], r.t_out[0]), (O, 0.0, 1.0))
        # Segments along x at height 1: short of the wall, ending on it, crossing it.
        r = certcyl.segment_cylinder([-3, 0, 1], [[-2, 0, 1], [-1, 0, 1], [0, 0, 1]], CYLINDER)
        self.assertEqual(r.answer.tolist(), [S, T, O])
        self.assertEqual((r.t_in[1], r.t_out[1]), (1.0, 1.0))
        self.assertEqual((r.t_in[2], r.t_out[2]), (2 / 3, 1.0))

    def test_elliptic_cylinders(self):
        # Semi-axes 1 along x and 2 along y, height 2: the line y = 2 is tangent, y = 0 crosses.
        e = [0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 2]
        r = certcyl.line_elliptic_cylinder([[-3, 0, 1], [-3, 2, 1], [-3, np.nextafter(2.0, 3.0), 1]], [1, 0, 0], e)
        self.assertEqual(r.answer.tolist(), [O, T, S])
        self.assertEqual((r.t_in[0], r.t_out[0]), (2.0, 4.0))
        self.assertEqual(certcyl.ray_elliptic_cylinder([-3, 0, 1], [-1, 0, 0], e).answer.tolist(), [S])
        self.assertEqual(certcyl.segment_elliptic_cylinder([-3, 0, 1], [-1, 0, 1], e).answer.tolist(), [T])
        self.assertEqual(certcyl.point_elliptic_cylinder([[0, 2, 1], [0, 1, 1], [0, 3, 1]], e).answer.tolist(), [T, O, S])

    def test_points(self):
        r = certcyl.point_cylinder([[0, 0, 1], [1, 0, 1], [0, 0, 2], [2, 0, 1], [0, 0, -1]], CYLINDER)
        self.assertEqual(r.answer.tolist(), [O, T, T, S, S])
        self.assertIsNone(r.t_in)
        # The centre's depth margin is min(1 - 0, 1/2, 1/2, 1) = 1/2.
        self.assertEqual(r.gap[0].tolist(), [0.5, 0.5])

    def test_triangles(self):
        # A triangle in the plane z = 3 (above), one in the cap plane z = 2 over the axis, and one
        # standing across the cylinder; given as N x 3 x 3 and as N x 9.
        tri = np.array([[[-1, -1, 3], [1, -1, 3], [0, 1, 3]],
                        [[-1, -1, 2], [1, -1, 2], [0, 1, 2]],
                        [[-3, 0, 0.5], [3, 0, 0.5], [0, 0, 1.5]]], dtype=np.float64)
        expected = [S, T, O]
        self.assertEqual(certcyl.triangle_cylinder(tri, CYLINDER).answer.tolist(), expected)
        self.assertEqual(certcyl.triangle_cylinder(tri.reshape(3, 9), CYLINDER).answer.tolist(), expected)

    def test_cylinder_pairs(self):
        # Parallel cylinders of radius 1 with axes 2 apart touch along a line; 1 apart they
        # overlap; radius 1/2 at distance 2 they are separated. Stacked cap to cap they touch.
        b = np.array([[2, 0, 0, 2, 0, 2, 1], [1, 0, 0, 1, 0, 2, 1], [2, 0, 0, 2, 0, 2, 0.5], [0, 0, 2, 0, 0, 4, 1]], dtype=np.float64)
        r = certcyl.cylinder_cylinder(CYLINDER, b, threads=2)
        self.assertEqual(r.answer.tolist(), [T, O, S, T])
        self.assertTrue(r.gap[1, 0] > 0 and r.gap[2, 1] < 0)
        self.assertTrue(r.gap[0, 0] <= 0 <= r.gap[0, 1])

    def test_threads_give_the_same_answers(self):
        rng = np.random.default_rng(20)
        n = 2000
        origins = rng.uniform(-3, 3, (n, 3))
        directions = rng.uniform(-1, 1, (n, 3))
        one = certcyl.ray_cylinder(origins, directions, CYLINDER, threads=1)
        four = certcyl.ray_cylinder(origins, directions, CYLINDER, threads=4)
        np.testing.assert_array_equal(one.answer, four.answer)
        np.testing.assert_array_equal(one.t_in, four.t_in)
        np.testing.assert_array_equal(one.gap, four.gap)
        self.assertTrue(set(one.answer.tolist()) >= {S, O})

    def test_cylinders_from_center(self):
        c = certcyl.cylinders_from_center([[0, 0, 1]], [0, 0, 1], 1, 2)
        self.assertEqual(c.tolist(), [CYLINDER.tolist()])
        with self.assertRaisesRegex(ValueError, r"axes: expected shape \(N, 3\)"):
            certcyl.cylinders_from_center([0, 0, 1], [0, 1], 1, 2)


class SameAsTheCommand(unittest.TestCase):
    """The study's hard cases (tangent lines, rim grazes, near-parallel directions at a few ulps
    from their degeneracy): the module's answers, intervals and gaps are those of `certcyl query`
    and of the cases' certified meta data."""

    def cases(self, query):
        lines = [json.loads(l) for l in command(["cases", "--query", query, "--size", "tiny"], "").splitlines()]
        self.assertGreater(len(lines), 20)
        return lines

    def test_line_queries(self):
        for query, member, first, second in (("line_cylinder", "line", "origin", "direction"),
                                             ("ray_cylinder", "ray", "origin", "direction"),
                                             ("segment_cylinder", "segment", "p0", "p1")):
            with self.subTest(query=query):
                cases = self.cases(query)
                a = np.array([c[member][first] for c in cases])
                b = np.array([c[member][second] for c in cases])
                cyl = np.array([c["cylinder"]["p0"] + c["cylinder"]["p1"] + [c["cylinder"]["radius"]] for c in cases])
                r = getattr(certcyl, query)(a, b, cyl)
                answers = [json.loads(l) for l in command(["query", "--brief"], "".join(json.dumps(c) + "\n" for c in cases)).splitlines()]
                for i, (c, q) in enumerate(zip(cases, answers)):
                    self.assertEqual(r.answer[i], CODES[q["answer"]], c["id"])
                    self.assertEqual(r.answer[i], CODES[c["meta"]["certified"]], c["id"])
                    ends = q["interval"] or [math.nan, math.nan]
                    np.testing.assert_array_equal([r.t_in[i], r.t_out[i]], ends, c["id"])
                    self.assertEqual(r.gap[i].tolist(), c["meta"]["gap"], c["id"])
                    self.assertEqual(q["gap_quantity"], c["meta"]["gap_quantity"], c["id"])
                self.assertEqual(r.gap_quantity, "depth_margin")
                self.assertEqual({c["meta"]["gap_quantity"] for c in cases}, {"depth_margin"})

    def answers_of(self, lines):
        """`certcyl query --brief`'s answers to the query lines (dicts)."""
        text = "".join(json.dumps(l) + "\n" for l in lines)
        return [json.loads(l) for l in command(["query", "--brief"], text).splitlines()]

    def assertSameAsCommand(self, r, lines, ids, intervals=True):
        answers = self.answers_of(lines)
        self.assertEqual(len(answers), len(lines))
        for i, q in enumerate(answers):
            self.assertNotIn("error", q, ids[i])
            self.assertEqual(r.answer[i], CODES[q["answer"]], ids[i])
            if intervals:
                ends = q["interval"] or [math.nan, math.nan]
                np.testing.assert_array_equal([r.t_in[i], r.t_out[i]], ends, ids[i])
        return answers

    def test_elliptic_line_ray_and_segment_queries(self):
        # The study's elliptic cases (a line tangent to the wall at a few ulps, rim grazes) as
        # lines, as rays from the same origin, as rays reversed, and as segments from the origin
        # to origin + 2 direction and back: the module's answers and intervals are the command's.
        cases = [json.loads(l) for l in command(["cases", "--query", "line_elliptic_cylinder", "--size", "tiny"], "").splitlines()]
        self.assertGreater(len(cases), 10)
        e_of = lambda e: e["base"] + e["a"] + e["b"] + e["c"]
        ell = np.array([e_of(c["elliptic_cylinder"]) for c in cases])
        o = np.array([c["line"]["origin"] for c in cases])
        d = np.array([c["line"]["direction"] for c in cases])
        ids = [c["id"] for c in cases]
        r = certcyl.line_elliptic_cylinder(o, d, ell)
        self.assertSameAsCommand(r, cases, ids)
        for i, c in enumerate(cases):
            self.assertEqual(r.answer[i], CODES[c["meta"]["certified"]], c["id"])
            self.assertEqual(r.gap[i].tolist(), c["meta"]["gap"], c["id"])
        elliptic = lambda i: dict(zip(("base", "a", "b", "c"), (ell[i, k:k + 3].tolist() for k in (0, 3, 6, 9))))
        for sign in (1, -1):
            r = certcyl.ray_elliptic_cylinder(o, sign * d, ell)
            lines = [{"id": i, "query": "ray_elliptic_cylinder", "ray": {"origin": o[i].tolist(), "direction": (sign * d[i]).tolist()},
                      "elliptic_cylinder": elliptic(i)} for i in range(len(cases))]
            self.assertSameAsCommand(r, lines, ids)
        far = o + 2 * d
        for p0, p1 in ((o, far), (far, o)):
            r = certcyl.segment_elliptic_cylinder(p0, p1, ell)
            lines = [{"id": i, "query": "segment_elliptic_cylinder", "segment": {"p0": p0[i].tolist(), "p1": p1[i].tolist()},
                      "elliptic_cylinder": elliptic(i)} for i in range(len(cases))]
            self.assertSameAsCommand(r, lines, ids)
        # Random rows, one elliptic cylinder broadcast: a mix of answers, the command's again.
        rng = np.random.default_rng(21)
        e = np.array([0.5, -0.25, -1, 1.5, 0.25, 0, -0.5, 0.75, 0.125, 0, 0.25, 2])
        o, d = rng.uniform(-3, 3, (200, 3)), rng.uniform(-1, 1, (200, 3))
        for query, member, first, second in (("line_elliptic_cylinder", "line", "origin", "direction"),
                                             ("ray_elliptic_cylinder", "ray", "origin", "direction"),
                                             ("segment_elliptic_cylinder", "segment", "p0", "p1")):
            with self.subTest(query=query):
                r = getattr(certcyl, query)(o, d, e, threads=2)
                lines = [{"id": i, "query": query, member: {first: o[i].tolist(), second: d[i].tolist()},
                          "elliptic_cylinder": dict(zip(("base", "a", "b", "c"), (e[k:k + 3].tolist() for k in (0, 3, 6, 9))))}
                         for i in range(len(o))]
                self.assertSameAsCommand(r, lines, list(range(len(o))))
                self.assertTrue({S, O} <= set(r.answer.tolist()), query)

    def test_point_queries(self):
        # Points on the boundary by construction (the ends of the axis: cap centres; for elliptic
        # cylinders base + a, a rim point), inside (the middle of the axis), the entry points of
        # the study's line cases (rounded: a few ulps from the wall), the lines' origins, and
        # random points: the command's answers.
        cases = self.cases("line_cylinder")
        points, cylinders = [], []
        for c in cases:
            cyl = c["cylinder"]
            p0, p1 = np.array(cyl["p0"]), np.array(cyl["p1"])
            r = certcyl.line_cylinder(c["line"]["origin"], c["line"]["direction"], cyl["p0"] + cyl["p1"] + [cyl["radius"]])
            near = [] if math.isnan(r.t_in[0]) else [np.array(c["line"]["origin"]) + r.t_in[0] * np.array(c["line"]["direction"])]
            for x in [p0, p1, (p0 + p1) / 2, np.array(c["line"]["origin"])] + near:
                points.append(x)
                cylinders.append(cyl["p0"] + cyl["p1"] + [cyl["radius"]])
        rng = np.random.default_rng(22)
        for _ in range(100):
            points.append(rng.uniform(-2, 2, 3))
            cylinders.append([0, 0, -1, 0.25, 0.5, 1.5, 1.25])
        points, cylinders = np.array(points), np.array(cylinders)
        r = certcyl.point_cylinder(points, cylinders)
        lines = [{"id": i, "query": "point_cylinder", "point": points[i].tolist(),
                  "cylinder": {"p0": cylinders[i, 0:3].tolist(), "p1": cylinders[i, 3:6].tolist(), "radius": cylinders[i, 6]}}
                 for i in range(len(points))]
        self.assertSameAsCommand(r, lines, list(range(len(points))), intervals=False)
        self.assertEqual(set(r.answer.tolist()), {S, T, O})
        self.assertEqual(r.answer[0], T)  # p0 of the first case: the centre of a cap
        # The gap's sign is the answer's.
        self.assertTrue(np.all(r.gap[r.answer == O, 0] > 0) and np.all(r.gap[r.answer == S, 1] < 0))
        self.assertTrue(np.all(r.gap[r.answer == T] == 0))

        cases = [json.loads(l) for l in command(["cases", "--query", "line_elliptic_cylinder", "--size", "tiny"], "").splitlines()]
        points, cylinders = [], []
        for c in cases:
            e = c["elliptic_cylinder"]
            row = e["base"] + e["a"] + e["b"] + e["c"]
            base, a, cz = np.array(e["base"]), np.array(e["a"]), np.array(e["c"])
            r = certcyl.line_elliptic_cylinder(c["line"]["origin"], c["line"]["direction"], row)
            near = [] if math.isnan(r.t_in[0]) else [np.array(c["line"]["origin"]) + r.t_in[0] * np.array(c["line"]["direction"])]
            for x in [base, base + a, base + cz / 2, np.array(c["line"]["origin"])] + near:
                points.append(x)
                cylinders.append(row)
        points, cylinders = np.array(points), np.array(cylinders)
        r = certcyl.point_elliptic_cylinder(points, cylinders)
        elliptic = lambda i: dict(zip(("base", "a", "b", "c"), (cylinders[i, k:k + 3].tolist() for k in (0, 3, 6, 9))))
        lines = [{"id": i, "query": "point_elliptic_cylinder", "point": points[i].tolist(), "elliptic_cylinder": elliptic(i)}
                 for i in range(len(points))]
        self.assertSameAsCommand(r, lines, list(range(len(points))), intervals=False)
        self.assertEqual(set(r.answer.tolist()), {S, T, O})
        self.assertEqual(r.answer[0], T)  # base: the centre of the bottom cap

    def test_triangles_and_pairs(self):
        cases = self.cases("triangle_cylinder")
        tri = np.array([c["triangle"] for c in cases])
        cyl = np.array([c["cylinder"]["p0"] + c["cylinder"]["p1"] + [c["cylinder"]["radius"]] for c in cases])
        r = certcyl.triangle_cylinder(tri, cyl)
        for i, c in enumerate(cases):
            self.assertEqual(r.answer[i], CODES[c["meta"]["certified"]], c["id"])
            self.assertEqual(r.gap[i].tolist(), c["meta"]["gap"], c["id"])
        cases = self.cases("cylinder_cylinder")
        as_rows = lambda c: c["p0"] + c["p1"] + [c["radius"]]
        r = certcyl.cylinder_cylinder(np.array([as_rows(c["a"]) for c in cases]), np.array([as_rows(c["b"]) for c in cases]))
        answers = [json.loads(l) for l in command(["query", "--brief"], "".join(json.dumps(c) + "\n" for c in cases)).splitlines()]
        self.assertEqual(r.gap_quantity, "log_phi")
        self.assertIsNone(certcyl.cylinder_cylinder(np.array([as_rows(cases[0]["a"])]), np.array([as_rows(cases[0]["b"])]),
                                                    gap=False).gap_quantity)
        for i, (c, q) in enumerate(zip(cases, answers)):
            self.assertEqual(r.answer[i], CODES[q["answer"]], c["id"])
            self.assertEqual((q["gap_quantity"], c["meta"]["gap_quantity"]), ("log_phi", "log_phi"), c["id"])
            # log(phi*) enclosed as the command encloses it (unbounded: equal midpoints).
            self.assertEqual(r.gap[i].tolist(), q["gap"] if q["gap"] is not None else [math.inf, math.inf], c["id"])


class BadInput(unittest.TestCase):
    def test_shapes_and_dtypes_name_the_argument(self):
        with self.assertRaisesRegex(ValueError, r"line_cylinder: cylinders: expected shape \(N, 7\) or \(7,\), got \(2, 6\)"):
            certcyl.line_cylinder([[0, 0, 0]], [[1, 0, 0]], np.zeros((2, 6)))
        with self.assertRaisesRegex(ValueError, r"directions has 3 rows and cylinders 2"):
            certcyl.line_cylinder([0, 0, 0], np.ones((3, 3)), np.tile(CYLINDER, (2, 1)))
        with self.assertRaisesRegex(ValueError, r"origins: dtype complex128"):
            certcyl.line_cylinder(np.zeros((1, 3), dtype=complex), [1, 0, 0], CYLINDER)
        with self.assertRaisesRegex(ValueError, r"points: dtype int64 holds a value that is not a binary64 value"):
            certcyl.point_cylinder(np.array([[2**53 + 1, 0, 0]], dtype=np.int64), CYLINDER)
        with self.assertRaisesRegex(ValueError, r"triangles: expected shape \(N, 9\)"):
            certcyl.triangle_cylinder(np.zeros((2, 4, 3)), CYLINDER)
        with self.assertRaisesRegex(ValueError, r"cylinder_cylinder: a: dtype object is not a real dtype"):
            certcyl.cylinder_cylinder(object(), CYLINDER)

    def test_a_negative_thread_count_is_a_value_error(self):
        for function, operands in ((certcyl.ray_cylinder, ([0, 0, 0], [1, 0, 0], CYLINDER)),
                                   (certcyl.segment_elliptic_cylinder, ([0, 0, 0], [1, 0, 0], np.r_[0, 0, 0, np.eye(3).ravel()])),
                                   (certcyl.point_cylinder, ([0, 0, 0], CYLINDER)),
                                   (certcyl.triangle_cylinder, (np.eye(3), CYLINDER)),
                                   (certcyl.cylinder_cylinder, (CYLINDER, CYLINDER))):
            with self.assertRaisesRegex(ValueError, function.__name__ + r": threads: expected 0 \(every core\) or a positive "
                                        r"number of threads, got -1"):
                function(*operands, threads=-1)
        self.assertEqual(certcyl.point_cylinder([0, 0, 1], CYLINDER, threads=0).answer.tolist(), [O])
        with self.assertRaisesRegex(ValueError, r"judge: threads: .* got -2"):
            certcyl.judge(lambda *a: 0, "line_cylinder", "tiny", threads=-2)

    def test_rows_the_library_rejects_name_the_row_and_the_field(self):
        origins = np.array([[-3, 0, 1], [-3, np.nan, 1]])
        with self.assertRaises(certcyl.InvalidInput) as e:
            certcyl.line_cylinder(origins, [1, 0, 0], CYLINDER)
        self.assertIsInstance(e.exception, ValueError)
        self.assertEqual(e.exception.row, 1)
        self.assertIn("line.origin", e.exception.field)
        self.assertIn("line_cylinder: row 1: ", str(e.exception))
        cylinders = np.array([CYLINDER, CYLINDER, [0, 0, 0, 0, 0, 2, -1.0]])
        with self.assertRaises(certcyl.InvalidInput) as e:
            certcyl.point_cylinder([0, 0, 1], cylinders, threads=3)
        self.assertEqual(e.exception.row, 2)
        self.assertIn("radius", e.exception.field)
        self.assertIn("must be positive", str(e.exception))
        with self.assertRaisesRegex(certcyl.InvalidInput, r"row 0: .*direction"):
            certcyl.ray_cylinder([0, 0, 0], [0, 0, 0], CYLINDER)
        with self.assertRaisesRegex(certcyl.InvalidInput, r"cylinder_cylinder: row 0: b\.p1\[2\]: non-finite number"):
            certcyl.cylinder_cylinder(CYLINDER, [0, 0, 0, 0, 0, np.inf, 1])


class OneExactQuery(unittest.TestCase):
    def test_fractions_in_and_out(self):
        r = certcyl.query("point_cylinder", point=[Fraction(3, 5), "4/5", 1],
                          cylinder={"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1})
        self.assertEqual((r.answer, r.code, r.certified), ("touching", T, True))
        self.assertEqual(r.certificate["point"], [Fraction(3, 5), Fraction(4, 5), Fraction(1)])
        self.assertIn("touching (certified", repr(r))
        # On the wall, the point's depth margin is 0.
        self.assertEqual((r.gap, r.gap_quantity), ([0.0, 0.0], "depth_margin"))
        # 0.6 as a float is not 3/5: the point is off the wall, and the method says so exactly.
        r = certcyl.query("point_cylinder", point=[0.6, 0.8, 1], cylinder={"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1})
        self.assertNotEqual(r.answer, "touching")

    def test_other_methods_and_errors(self):
        line = {"origin": [-3, 1, 1], "direction": [1, 0, 0]}
        r = certcyl.query("line_cylinder", method="shene", nt="double", line=line,
                          cylinder={"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1})
        self.assertEqual((r.method, r.nt, r.certified), ("shene", "double", False))
        self.assertEqual((r.gap, r.gap_quantity), (None, None))  # only the certified method has a gap
        with self.assertRaisesRegex(ValueError, r"cylinder.radius: must be positive, got -1"):
            certcyl.query("point_cylinder", point=[0, 0, 0], cylinder={"p0": [0, 0, 0], "p1": [0, 0, 1], "radius": -1})
        with self.assertRaisesRegex(ValueError, r"point\[0\]: not a finite number"):
            certcyl.query("point_cylinder", point=[math.nan, 0, 0], cylinder={"p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 1})


class Judge(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.cases = [json.loads(l) for l in command(["cases", "--query", "line_cylinder", "--size", "tiny"], "").splitlines()]
        self.meeting = sum(c["meta"]["certified"] != "separated" for c in self.cases)

    def tearDown(self):
        self.tmp.cleanup()

    def judge(self, function, size="tiny", **options):
        return certcyl.judge(function, "line_cylinder", size, out=self.tmp.name, **options)

    def test_intervals_are_scored_against_the_certified_entry_parameter(self):
        # The certified query's own interval: every meeting case scored, every error 0. Moved by
        # two ulps of max(|t|, 1): errors of 2 (3 where the sum rounds across a power of two).
        # As a vectorized function returning (answer, t_in, t_out) rows, and with t_out None.
        def certified(shift):
            def method(origin, direction, cylinder):
                r = certcyl.line_cylinder(origin, direction, cylinder)
                rows = []
                for a, t_in, t_out in zip(r.answer, r.t_in, r.t_out):
                    t = float(t_in)
                    if not math.isnan(t):
                        t += shift * math.ulp(max(abs(t), 1.0))
                    rows.append((int(a), None if math.isnan(t) else t, None if shift else float(t_out)))
                return rows
            return method
        exact = self.judge(certified(0), vectorized=True, name="exact_t").family("line_cylinder")
        self.assertEqual(exact["t_errors"], self.meeting)
        self.assertEqual((exact["t_error_median_ulps"], exact["t_error_max_ulps"]), (0.0, 0.0))
        moved = self.judge(certified(2), vectorized=True, name="moved_t").family("line_cylinder")
        self.assertEqual(moved["t_errors"], self.meeting)
        self.assertEqual(moved["t_error_median_ulps"], 2.0)
        self.assertLessEqual(moved["t_error_max_ulps"], 3.0)
        self.assertGreaterEqual(moved["t_error_max_ulps"], 2.0)
        # A pair that is not (answer, t_in[, t_out]) is an error naming the case.
        with self.assertRaisesRegex(ValueError, "may return \\(answer, t_in\\)"):
            self.judge(lambda o, d, c: ("separated", 0.0, 1.0, 2.0), name="bad_t")

    def test_the_certified_answers_agree_everywhere(self):
        def certified(origin, direction, cylinder):
            return int(certcyl.line_cylinder(origin, direction, cylinder).answer[0])
        total = self.judge(certified, name="certified").family("line_cylinder")
        self.assertEqual(total["cases"], len(self.cases))
        self.assertEqual(total["agree"], len(self.cases))
        self.assertEqual(total["failures"], 0)

    def test_a_method_that_never_meets_fails_on_every_meeting_case(self):
        shapes = []
        def never(origins, directions, cylinders):
            shapes.append((origins.shape, cylinders.shape))
            return np.zeros(len(origins), dtype=bool)
        result = self.judge(never, vectorized=True, name="never", method="never")
        # One call with every case, then one with every cell of the two maps (16 x 16 each at
        # tiny size), then one per input of the hunt.
        self.assertEqual(shapes[0], ((len(self.cases), 3), (len(self.cases), 7)))
        self.assertEqual(shapes[1], ((2 * 16 * 16, 3), (2 * 16 * 16, 7)))
        self.assertEqual(set(shapes[2:]), {((1, 3), (1, 7))})
        total = result.family("line_cylinder")
        self.assertEqual(total["false_negative"], self.meeting)
        self.assertEqual(total["failures"], self.meeting)
        self.assertEqual(total["agree"], len(self.cases) - self.meeting)
        self.assertTrue(result.summary.startswith("certcyl judge: never, "))
        with open(os.path.join(result.folder, "counterexamples.jsonl")) as f:
            self.assertGreater(len(f.readlines()), 0)
        # The one-page report opens on the failure count.
        with open(os.path.join(result.folder, "index.html"), encoding="utf-8") as f:
            self.assertIn(f"<b>{self.meeting} failure{'' if self.meeting == 1 else 's'}</b>", f.read())

    def test_a_ray_cast_is_judged_under_its_contract(self):
        # A ray cast reporting entries only, built from the module's certified queries: the
        # certified solid answer, and no hit when the origin lies in the cylinder (point_cylinder
        # not separated). Under surface_entry it is never wrong; under solid its misses from
        # inside are false negatives, counted here from the same certified queries.
        def entry(origins, directions, cylinders):
            solid = certcyl.ray_cylinder(origins, directions, cylinders, gap=False).answer
            inside = certcyl.point_cylinder(origins, cylinders, gap=False).answer != S
            return np.where(inside, S, solid)
        cases = [json.loads(l) for l in command(["cases", "--query", "ray_cylinder", "--size", "tiny"], "").splitlines()]
        o = np.array([c["ray"]["origin"] for c in cases])
        cyl = np.array([c["cylinder"]["p0"] + c["cylinder"]["p1"] + [c["cylinder"]["radius"]] for c in cases])
        starts_in = (certcyl.point_cylinder(o, cyl, gap=False).answer != S) & \
            (np.array([c["meta"]["certified"] for c in cases]) != "separated")
        self.assertGreater(int(starts_in.sum()), 0)  # the tiny cases hold rays starting in the cylinder
        options = dict(vectorized=True, out=self.tmp.name, map_cells=0, hunt_evaluations=0)
        under_entry = certcyl.judge(entry, "ray_cylinder", "tiny", name="entry", contract="surface_entry", **options)
        self.assertEqual(under_entry.family("ray_cylinder")["failures"], 0)
        self.assertIn("under the contract surface_entry", under_entry.summary)
        under_solid = certcyl.judge(entry, "ray_cylinder", "tiny", name="solid", **options)
        total = under_solid.family("ray_cylinder")
        self.assertEqual((total["false_negative"], total["false_positive"]), (int(starts_in.sum()), 0))
        with self.assertRaisesRegex(ValueError, "judge: contract: expected solid, surface_entry or surface_hit, got 'entry'"):
            certcyl.judge(entry, "ray_cylinder", "tiny", contract="entry", **options)
        with self.assertRaisesRegex(ValueError, "judge: contract surface_hit: defined for ray_cylinder and segment_cylinder only"):
            certcyl.judge(entry, "line_cylinder", "tiny", contract="surface_hit", **options)

    def test_judged_as_the_command_judges_the_same_answers(self):
        # A naive double test (the distance of the line to the axis' line, caps ignored), judged
        # in process, and its answers to the same cases written to an answers file and judged by
        # `certcyl judge --answers`: the same families.csv.
        def naive(origin, direction, cylinder):
            p0, p1, r = cylinder[:3], cylinder[3:6], cylinder[6]
            n = np.cross(direction, p1 - p0)
            if not np.any(n):
                return "undecided"
            d = abs(np.dot(origin - p0, n)) / np.linalg.norm(n)
            return certcyl.OVERLAPPING if d < r else certcyl.TOUCHING if d == r else certcyl.SEPARATED
        result = self.judge(naive, "small", name="naive", method="naive")
        total = result.family("line_cylinder")
        self.assertGreater(total["failures"], 0)  # the comparison is not only of zeros
        cases_file = os.path.join(self.tmp.name, "cases.jsonl")
        answers_file = os.path.join(self.tmp.name, "naive.jsonl")
        with open(cases_file, "w") as f:
            f.write(command(["cases", "--query", "line_cylinder", "--size", "small"], ""))
        words = {S: "separated", T: "touching", O: "overlapping"}
        with open(cases_file) as cases, open(answers_file, "w") as out:
            for line in cases:
                c = json.loads(line)
                cyl = np.array(c["cylinder"]["p0"] + c["cylinder"]["p1"] + [c["cylinder"]["radius"]])
                a = naive(np.array(c["line"]["origin"]), np.array(c["line"]["direction"]), cyl)
                out.write(json.dumps({"id": c["id"], "answer": words.get(a, a)}) + "\n")
        command(["judge", "--cases", cases_file, "--answers", answers_file, "--label", "naive", "--out", self.tmp.name,
                 "--name", "command"], "")
        with open(os.path.join(self.tmp.name, "command", "families.csv")) as a, open(os.path.join(result.folder, "families.csv")) as b:
            self.assertEqual(a.read(), b.read())

    def test_maps_and_hunt_as_the_command_draws_them(self):
        # The example program of `certcyl judge --exec` (examples/exec_python/line_double.py),
        # judged by the command and, through its clip function, in process: the same families,
        # counterexamples, failure maps (every cell) and hunt, byte for byte.
        example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "exec_python")
        sys.path.insert(0, example)
        try:
            from line_double import clip
        finally:
            sys.path.remove(example)

        def line_double(origin, direction, cylinder):
            c = [float(x) for x in cylinder]
            return clip([float(x) for x in origin], [float(x) for x in direction], {"p0": c[:3], "p1": c[3:6], "radius": c[6]},
                        -math.inf, math.inf)

        def vectorized(origins, directions, cylinders):
            return [line_double(o, d, c) for o, d, c in zip(origins, directions, cylinders)]

        with np.errstate(all="ignore"):
            result = self.judge(line_double, name="inproc", method="line_double")
            batched = self.judge(vectorized, name="batched", method="line_double", vectorized=True)
        command(["judge", "--exec", f"{sys.executable} {os.path.join(example, 'line_double.py')}", "--query", "line_cylinder",
                 "--size", "tiny", "--label", "line_double", "--out", self.tmp.name, "--name", "command"], "")

        def read(name, file):
            with open(os.path.join(self.tmp.name, name, file)) as f:
                return f.read()
        maps = sorted(os.listdir(os.path.join(self.tmp.name, "command", "failure_maps")))
        self.assertGreater(len(maps), 0)
        # The in-process calls are timed (speed.csv, as the command writes it for a program).
        with open(os.path.join(result.folder, "speed.csv")) as f:
            rows = f.read().splitlines()
        self.assertEqual(len(rows), 2)
        self.assertGreater(float(rows[1].split(",")[-1]), 0)
        files = ["families.csv", "counterexamples.jsonl", "answers.jsonl", "failure_maps.csv", "hunt.csv"]
        for name in ("inproc", "batched"):
            for file in files + [os.path.join("failure_maps", m) for m in maps]:
                self.assertEqual(read(name, file), read("command", file), f"{name}: {file}")
        # The maps find the test's failures (its discriminant's rounding near tangency).
        wrong = [int(row.split(",")[-1]) for row in read("inproc", "failure_maps.csv").splitlines()[1:]]
        self.assertGreater(sum(wrong), 0)
        self.assertIn("failure map", result.summary)
        self.assertIn("hunt: line_cylinder", result.summary)

        # Without maps and hunt; bad sizes.
        plain = self.judge(line_double, name="plain", map_cells=0, hunt_evaluations=0)
        self.assertFalse(os.path.exists(os.path.join(plain.folder, "failure_maps")))
        self.assertFalse(os.path.exists(os.path.join(plain.folder, "hunt.csv")))
        for bad in ({"map_cells": 1}, {"map_cells": 2.5}, {"hunt_evaluations": -3}, {"map_step": 0}):
            with self.assertRaisesRegex(ValueError, f"judge: {next(iter(bad))}: expected"):
                self.judge(line_double, name="bad", **bad)

    def test_an_exception_in_the_maps_keeps_what_was_judged(self):
        calls = []
        def fails_in_the_maps(origin, direction, cylinder):
            calls.append(1)
            if len(calls) == len(self.cases) + 5:
                raise RuntimeError("broken in a map")
            return certcyl.SEPARATED
        with self.assertRaisesRegex(RuntimeError, "broken in a map"):
            self.judge(fails_in_the_maps, name="maps")
        folder = os.path.join(self.tmp.name, "maps")
        with open(os.path.join(folder, "answers.jsonl")) as f:
            self.assertEqual(len(f.readlines()), len(self.cases))
        with open(os.path.join(folder, "summary.txt")) as f:
            self.assertIn("broken in a map", f.read())
        self.assertEqual(len(calls), len(self.cases) + 5)  # no call after the exception

    def test_an_exception_keeps_what_was_judged(self):
        calls = []
        def fails_on_the_fourth(origin, direction, cylinder):
            calls.append(1)
            if len(calls) == 4:
                raise RuntimeError("broken")
            return certcyl.SEPARATED
        with self.assertRaisesRegex(RuntimeError, "broken"):
            self.judge(fails_on_the_fourth, name="fails")
        with open(os.path.join(self.tmp.name, "fails", "answers.jsonl")) as f:
            self.assertEqual(len(f.readlines()), 3)
        with self.assertRaisesRegex(ValueError, r"case line_cylinder/.*: answer code 9"):
            self.judge(lambda o, d, c: 9, name="bad")
        with self.assertRaisesRegex(ValueError, r"judge: query: expected one of"):
            certcyl.judge(lambda *a: 0, "no_such_query")


if __name__ == "__main__":
    CERTCYL = sys.argv.pop(1)
    unittest.main()
