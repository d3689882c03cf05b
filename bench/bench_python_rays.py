"""The Python module against the C++ library on the same random rays, side by side in one run.

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_python_rays.py build/bench/bench_python_rays_cpp
        [--rays 1000000] [--gap-rays 100000] [--calls 20000] [--repeats 1] [--seed 20]

N random rays and lines (origins in [-3, 3]^3, each towards a random point of [-1.5, 1.5]^3)
against N random cylinders (p0, p1 in [-1, 1]^3, radius in [0.05, 1]) are answered by the
certified query

- in C++ (bench_python_rays_cpp: a loop over the rows, as the module runs them), and
- in Python: certcyl.ray_cylinder and certcyl.line_cylinder on the N rows at once, one thread,
  with gap=False and (on the first GAP_RAYS rows) with the default gap=True, the exact rational
  depth margin;

then single queries: a batch of one row (gap=False and the default) and certcyl.query (the
JSON line of `certcyl query`, parsed back with Fractions), CALLS calls each (certcyl.query:
CALLS / 10). Prints ns per row of each, the Python/C++ ratios and the per-call overhead (a single
call's time less the time per row of one batch of the same rows). With --repeats R the C++ and the Python batches run
R times alternately and the medians are reported (the machine's load moves both together).

Exit status 1 when any answer, t_in, t_out or gap of the module differs from the C++ one, or a
single query's answer from the batch's; the timings are reported, never checked.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import certcyl


def random_rows(n, seed):
    rng = np.random.default_rng(seed)
    rows = np.empty((n, 13))
    rows[:, 0:3] = rng.uniform(-3, 3, (n, 3))
    rows[:, 3:6] = rng.uniform(-1.5, 1.5, (n, 3)) - rows[:, 0:3]  # towards a point near the cylinders
    rows[:, 6:12] = rng.uniform(-1, 1, (n, 6))
    rows[:, 12] = rng.uniform(0.05, 1, n)
    return rows


RUNS = ("line", "ray", "line_gap", "ray_gap")


def run_cpp(program, rows, gap_rows):
    """The C++ timings (ns per row) and results of each run, from bench_python_rays_cpp."""
    n = len(rows)
    done = subprocess.run([program, str(n), str(gap_rows)], input=np.ascontiguousarray(rows).tobytes(),
                          capture_output=True, check=True)
    newline = done.stdout.index(b"\n")
    timings = json.loads(done.stdout[:newline])
    data, at = done.stdout[newline + 1:], 0
    results = {}
    for name in RUNS:
        m = gap_rows if name.endswith("_gap") else n
        out = {}
        for field, dtype, count in (("answer", np.int8, m), ("t_in", np.float64, m), ("t_out", np.float64, m),
                                    ("gap", np.float64, 2 * m if name.endswith("_gap") else 0)):
            size = np.dtype(dtype).itemsize * count
            out[field] = np.frombuffer(data[at:at + size], dtype=dtype)
            at += size
        out["gap"] = out["gap"].reshape(-1, 2)
        results[name] = out
    if at != len(data):
        raise RuntimeError(f"bench_python_rays_cpp wrote {len(data)} bytes of results, expected {at}")
    return timings, results


def timed(function, *args, **kwargs):
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - start


def run_python(rows, gap_rows):
    """The module's timings (ns per row) and results of each run."""
    o, d, c = rows[:, 0:3], rows[:, 3:6], rows[:, 6:13]
    o, d, c = (np.ascontiguousarray(a) for a in (o, d, c))
    g = gap_rows
    calls = {
        "line": lambda: certcyl.line_cylinder(o, d, c, gap=False),
        "ray": lambda: certcyl.ray_cylinder(o, d, c, gap=False),
        "line_gap": lambda: certcyl.line_cylinder(o[:g], d[:g], c[:g]),
        "ray_gap": lambda: certcyl.ray_cylinder(o[:g], d[:g], c[:g]),
    }
    timings, results = {}, {}
    for name in RUNS:
        r, seconds = timed(calls[name])
        timings[name] = seconds * 1e9 / len(r)
        results[name] = {"answer": r.answer, "t_in": r.t_in, "t_out": r.t_out,
                         "gap": r.gap if r.gap is not None else np.empty((0, 2))}
    return timings, results


def compare(cpp, py):
    """Lines naming each difference between the C++ and the module's results."""
    problems = []
    for name in RUNS:
        for field in ("answer", "t_in", "t_out", "gap"):
            a, b = cpp[name][field], py[name][field]
            if a.shape != b.shape:
                problems.append(f"{name}.{field}: shape {a.shape} in C++, {b.shape} in Python")
                continue
            # Bit for bit, NaN equal to NaN (separated rows have NaN ends).
            same = (a == b) | (np.isnan(a) & np.isnan(b)) if a.dtype.kind == "f" else a == b
            bad = np.flatnonzero(~same.reshape(len(a), -1).all(axis=1)) if a.size else []
            if len(bad):
                i = bad[0]
                problems.append(f"{name}.{field}: {len(bad)} rows differ, first row {i}: C++ {a[i]}, Python {b[i]}")
    return problems


def single_calls(rows, calls, batch_answers):
    """ns per call of a batch of one (gap=False and the default) and of certcyl.query, and the
    rows whose single answer differs from the batch's."""
    k = min(calls, len(rows))
    singles = [(np.ascontiguousarray(r[0:3]), np.ascontiguousarray(r[3:6]), np.ascontiguousarray(r[6:13])) for r in rows[:k]]
    timings, problems = {}, []
    batch = [np.ascontiguousarray(rows[:k, a:b]) for a, b in ((0, 3), (3, 6), (6, 13))]
    for name, gap in (("one_row", False), ("one_row_gap", True)):
        _, seconds = timed(certcyl.ray_cylinder, *batch, gap=gap)
        timings[name + "_batch"] = seconds * 1e9 / k
        answers = np.empty(k, dtype=np.int8)
        start = time.perf_counter()
        for i, (o, d, c) in enumerate(singles):
            answers[i] = certcyl.ray_cylinder(o, d, c, gap=gap).answer[0]
        timings[name] = (time.perf_counter() - start) * 1e9 / k
        bad = np.flatnonzero(answers != batch_answers[:k])
        if len(bad):
            problems.append(f"{name}: {len(bad)} answers differ from the batch's, first row {bad[0]}")
    q = max(1, k // 10)
    operands = [({"origin": o.tolist(), "direction": d.tolist()}, {"p0": c[0:3].tolist(), "p1": c[3:6].tolist(), "radius": float(c[6])})
                for o, d, c in singles[:q]]
    answers = []
    start = time.perf_counter()
    for ray, cylinder in operands:
        answers.append(certcyl.query("ray_cylinder", ray=ray, cylinder=cylinder).code)
    timings["query"] = (time.perf_counter() - start) * 1e9 / q
    bad = np.flatnonzero(np.array(answers) != batch_answers[:q])
    if len(bad):
        problems.append(f"certcyl.query: {len(bad)} answers differ from the batch's, first row {bad[0]}")
    return timings, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cpp", help="the bench_python_rays_cpp program")
    parser.add_argument("--rays", type=int, default=1_000_000)
    parser.add_argument("--gap-rays", type=int, default=100_000, help="rows of the gap=True runs (default 10^5)")
    parser.add_argument("--calls", type=int, default=20_000, help="single calls timed (certcyl.query: a tenth)")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--seed", type=int, default=20)
    args = parser.parse_args()
    gap_rows = min(args.gap_rays, args.rays)
    rows = random_rows(args.rays, args.seed)

    cpp_times, py_times, problems = {n: [] for n in RUNS}, {n: [] for n in RUNS}, []
    for _ in range(args.repeats):
        cpp_t, cpp_r = run_cpp(args.cpp, rows, gap_rows)
        py_t, py_r = run_python(rows, gap_rows)
        for name in RUNS:
            cpp_times[name].append(cpp_t[name])
            py_times[name].append(py_t[name])
        problems += compare(cpp_r, py_r)
    single, single_problems = single_calls(rows, args.calls, py_r["ray"]["answer"])
    problems += single_problems

    counts = np.bincount(py_r["ray"]["answer"], minlength=3)
    print(f"certcyl Python module vs C++ library: {args.rays} random rows ({gap_rows} with the gap), "
          f"seed {args.seed}, one thread, median of {args.repeats} run(s), load average {os.getloadavg()[0]:.2f}")
    print(f"rays: {counts[0]} separated, {counts[1]} touching, {counts[2]} overlapping")
    print(f"{'query':<32}{'C++ ns/row':>12}{'Python ns/row':>15}{'Python/C++':>12}")
    for name, label in (("ray", "ray_cylinder gap=False"), ("line", "line_cylinder gap=False"),
                        ("ray_gap", "ray_cylinder (gap=True)"), ("line_gap", "line_cylinder (gap=True)")):
        c, p = statistics.median(cpp_times[name]), statistics.median(py_times[name])
        print(f"{label:<32}{c:>12.1f}{p:>15.1f}{p / c:>12.3f}")
    print(f"{'single call (' + str(min(args.calls, args.rays)) + ' calls)':<32}{'ns/call':>12}{'batch ns/row':>15}"
          f"{'overhead ns':>12}")
    for name, label, base in (("one_row", "ray_cylinder, 1 row, gap=False", "one_row_batch"),
                              ("one_row_gap", "ray_cylinder, 1 row (gap)", "one_row_gap_batch"),
                              ("query", "certcyl.query ray_cylinder", "one_row_batch")):
        print(f"{label:<32}{single[name]:>12.1f}{single[base]:>15.1f}{single[name] - single[base]:>12.1f}")
    if problems:
        print("DISAGREEMENTS between the module and the C++ library:", file=sys.stderr)
        for p in problems:
            print("  " + p, file=sys.stderr)
        return 1
    print("every answer, t_in, t_out and gap of the module equals the C++ library's")
    return 0


if __name__ == "__main__":
    sys.exit(main())
