#!/usr/bin/python3
"""ctest 'paper_results_helpers': the error measures the study's scripts share
(experiments/certcyl_results.py) and the failure maps' masks (experiments/plot_study.py), on rows
made by hand whose answers are known.

    /usr/bin/python3 tests/python/test_results_helpers.py SOURCE_DIR

Checks the bins of k at their edges, the Boolean and three-valued error of a set of outcomes, the
Wilson interval's exact ends, that errors_by_k leaves out the uniform family and undecided answers,
that boolean_methods finds the methods answering intersecting, that paired comparisons count only the
instances every compared method ran on, the timing statistics, and that a failure map's class
mismatches are neither false positives nor false negatives and never a Boolean method's.
Exit status 1 with one line per failed check; the map checks are skipped (said on standard output)
where numpy or matplotlib is missing.
"""
import math
import os
import sys

source = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(source, "experiments"))
import certcyl_results as cr  # noqa: E402

failures = []


def check(what, got, want):
    if got != want:
        failures.append(f"{what}: got {got!r}, expected {want!r}")


# Bins of k: 0, then four binades a bin, the last open (|k| >= 2^36).
check("bins", len(cr.K_BINS), 11)
for k, b in (("0", 0), ("-0.0", 0), ("1", 1), ("-15", 1), ("16", 2), ("255", 2), ("256", 3), (str(2 ** 36 - 1), 9),
             (str(2 ** 36), 10), (str(2 ** 40 + 2 ** 39), 10), (str(-2 ** 41), 10), ("", None)):
    check(f"k_bin({k})", cr.k_bin(k), b)
check("label of bin 0", cr.k_bin_label(0), "0")
check("label of bin 2", cr.k_bin_label(2), "[2^4, 2^8)")
check("label of the last bin", cr.k_bin_label(10), ">= 2^36")

# Errors: 10 decided (4 agree, 2 FP, 1 FN, 3 class), undecided, error and invalid not counted.
e = cr.Errors()
for o in ["agree"] * 4 + ["false_positive"] * 2 + ["false_negative"] + ["class_mismatch"] * 3 + ["undecided", "error", "invalid", "uncertified"]:
    e.add(o)
check("decided", e.decided, 10)
check("Boolean wrong", e.wrong, 3)
check("three-valued wrong", e.wrong3, 6)
check("Boolean rate", e.rate, 0.3)
check("three-valued rate", e.rate3, 0.6)
check("interval, Boolean", e.interval(), cr.wilson(3, 10))
check("interval, three-valued", e.interval(True), cr.wilson(6, 10))
t = cr.Errors.pooled([e, e])
check("pooled", (t.decided, t.fp, t.fn, t.cls), (20, 4, 2, 6))
check("nothing decided", math.isnan(cr.Errors().rate), True)
check("interval at 0 of 7", cr.error_interval(0, 7)[0], 0.0)
check("interval at 7 of 7", cr.error_interval(7, 7)[1], 1.0)
lo, hi = cr.error_interval(0, 7)
check("interval at 0 of 7 is Wilson's upper bound", hi, cr.wilson(0, 7)[1])
for p, text in ((0, "0"), (4.1e-5, "0.0041"), (0.035, "3.5"), (0.3712, "37"), (0.09996, "10"), (0.996, "100"), (1, "100")):
    check(f"percent_text({p})", cr.percent_text(p), text)
check("Wilson at 1 of 2 holds 1/2", cr.wilson(1, 2)[0] < 0.5 < cr.wilson(1, 2)[1], True)


def row(family, k, method, answer, outcome, query="line_cylinder"):
    return {"family": family, "k_ulps": k, "method": method, "answer": answer, "outcome": outcome, "query": query}


rows = [row("tangent", "0", "a/double", "overlapping", "class_mismatch"),
        row("tangent", "0", "a/double", "separated", "false_negative"),
        row("tangent", "-3", "a/double", "touching", "agree"),
        row("tangent", "70000", "a/double", "overlapping", "agree"),
        row("tangent", "5", "a/interval", "undecided", "undecided"),
        row("uniform", "0", "a/double", "separated", "false_negative"),
        row("tangent", "0", "b/double", "intersecting", "false_positive"),
        row("tangent", "1", "b/double", "intersecting", "agree")]
by_k = cr.errors_by_k(rows)
a = by_k[("line_cylinder", "a/double")]
check("a at k = 0: decided, Boolean, three-valued", (a[0].decided, a[0].wrong, a[0].wrong3), (2, 1, 2))
check("a at |k| = 3", (a[1].decided, a[1].wrong), (1, 0))
check("a at k = 70000 (bin [2^16, 2^20))", a[5].decided, 1)
check("a decided over all bins (uniform left out)", sum(b.decided for b in a), 4)
check("an undecided method has no bins", ("line_cylinder", "a/interval") in by_k, False)
check("Boolean methods", cr.boolean_methods(rows), {"b/double"})

# Paired comparisons: the instances every compared method ran on, and speed and error there only.
def row(query, method, instance, outcome="agree", ns="10", answer="separated", family="tangent"):
    return {"query": query, "method": method, "instance": str(instance), "outcome": outcome, "ns": ns, "answer": answer,
            "family": family}


prs = [row("q", "a/double", i, ns=str(i)) for i in range(1, 9)] + \
      [row("q", "a/core_expr", i, outcome="false_positive" if i == 4 else "agree", ns="1000") for i in (2, 4, 6)] + \
      [row("q", "a/double", 9, answer="process_ended", outcome="error"), row("r", "a/double", 1)]
check("paired", cr.paired(prs, "q", ["a/double", "a/core_expr"]), {"2", "4", "6"})
check("paired, a method that never ran", cr.paired(prs, "q", ["a/double", "b/double"]), set())
common, pts = cr.paired_speed_error(prs, "q", ["a/double", "a/core_expr"])
check("paired_speed_error instances", common, {"2", "4", "6"})
check("paired_speed_error double", pts["a/double"], (4.0, 0.0, 3))  # times 2, 4, 6: median 4, not that of 1..8
check("paired_speed_error core", pts["a/core_expr"], (1000.0, 1 / 3, 3))
# Paired per algorithm (the index page's summary): a's number types on instances 2, 4, 6 only; r's
# a/double alone keeps its instance; b (one number type) all of its instances.
pa = cr.paired_by_algorithm(prs + [row("q", "b/double", i, outcome="false_negative" if i == 1 else "agree") for i in (1, 3)])
check("paired_by_algorithm: a/double", (pa[("q", "a/double")].paired, pa[("q", "a/double")].n, pa[("q", "a/double")].median_ns), (3, 3, 4.0))
check("paired_by_algorithm: a/core_expr", (pa[("q", "a/core_expr")].errors.fp, pa[("q", "a/core_expr")].errors.decided), (1, 3))
check("paired_by_algorithm: r", (pa[("r", "a/double")].paired, pa[("r", "a/double")].n), (1, 1))
check("paired_by_algorithm: b", (pa[("q", "b/double")].paired, pa[("q", "b/double")].errors.fn), (2, 1))

# Wilson intervals against published values (95%): 0 of 10 is [0, 0.2775], 1 of 10 [0.0179,
# 0.4042]; 0 of n has the upper end z^2 / (n + z^2), z^2 = 3.8415, so 0 of 100,000 is below 3.84e-5.
lo, hi = cr.error_interval(0, 10)
check("Wilson 0 of 10", (lo, round(hi, 4)), (0.0, 0.2775))
lo, hi = cr.wilson(1, 10)
check("Wilson 1 of 10", (round(lo, 4), round(hi, 4)), (0.0179, 0.4042))
lo, hi = cr.error_interval(0, 100000)
check("Wilson 0 of 100000", (lo, round(hi * 1e5, 3)), (0.0, 3.841))
# 50 of 100,000: p = 5e-4, centre (p + z^2/2n) / (1 + z^2/n), half-width z / (1 + z^2/n) *
# sqrt(p(1-p)/n + z^2/4n^2): [3.79e-4, 6.59e-4] to three digits.
lo, hi = cr.wilson(50, 100000)
check("Wilson 50 of 100000", (round(lo * 1e4, 2), round(hi * 1e4, 2)), (3.79, 6.59))

# A row of uniform.csv: its counts make the Errors; a method with `intersecting` answers is Boolean.
urow = {"query": "line_cylinder", "method": "m/double", "kind": "robust", "instances": "1000", "separated": "600", "touching": "0",
        "overlapping": "399", "uncertified": "1", "decided": "990", "false_positive": "7", "false_negative": "3",
        "class_mismatch": "2", "undecided": "5", "error": "3", "invalid": "1", "intersecting": "0"}
ue = cr.uniform_errors(urow)
check("uniform_errors", (ue.decided, ue.wrong, ue.wrong3), (990, 10, 12))
check("uniform_errors interval", ue.interval(), cr.wilson(10, 990))
check("uniform three-valued", cr.uniform_boolean(urow), False)
check("uniform Boolean", cr.uniform_boolean(dict(urow, intersecting="400")), True)

# Times: nearest-rank percentiles and the mean summed left to right.
check("time_stats", cr.time_stats([5.0, 1.0, 3.0, 2.0, 4.0]), (5, 1.0, 3.0, 5.0, 3.0, 5.0))
check("time_stats of nothing", cr.time_stats([]), None)
check("input classes", (cr.input_class("uniform"), cr.input_class("c_rim_rim")), ("generic", "near_degenerate"))
check("ns_tex", (cr.ns_tex(81.4), cr.ns_tex(2440.0), cr.ns_tex(2.41e7), cr.ns_tex(math.nan)),
      ("81\\,ns", "2.44\\,\\ensuremath{\\mu}s", "24.1\\,ms", "--"))

# The failure maps' masks (plot_study.py): needs numpy and matplotlib.
try:
    import numpy as np
    import plot_study as ps
except ImportError as err:
    print(f"test_results_helpers: skipped the map masks ({err})")
    np = None
if np is not None:
    code = lambda s: np.array([[ps.CODES.index(c) for c in s]])  # noqa: E731
    cert = code("sttoos")
    # Certified -> answered, cell by cell: s -> t FP; t -> o class; t -> t right; o -> t class;
    # o -> s FN; s -> u undecided.
    fp, fn, cls = ps.wrong_counts(code("tottsu"), cert, np.ones(cert.shape, dtype=bool))
    check("map FP", fp.tolist(), [[True, False, False, False, False, False]])
    check("map FN", fn.tolist(), [[False, False, False, False, True, False]])
    check("map class", cls.tolist(), [[False, True, False, True, False, False]])
    fp, fn, cls = ps.wrong_counts(code("iiiiss"), cert, np.ones(cert.shape, dtype=bool))
    check("Boolean map: no class mismatch", cls.any(), False)
    check("Boolean map FP, FN", (fp.tolist(), fn.tolist()),
          ([[True, False, False, False, False, False]], [[False, False, False, False, True, False]]))

for f in failures:
    print("FAILED:", f)
print(f"test_results_helpers: {len(failures)} failures")
sys.exit(1 if failures else 0)
