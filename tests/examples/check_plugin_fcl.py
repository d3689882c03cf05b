#!/usr/bin/env python3
"""Checks examples/plugin_fcl (FCL's fcl::collide as a plugin) and its judgement. The plugin,
called here: it names itself "fcl <version>" and answers pairs placed by hand, whose answers a
misplaced or misoriented FCL shape would flip. The judgement, against the cases `certcyl cases`
makes on its own: the report names the plugin, every case of its queries (cylinder_cylinder,
triangle_cylinder) is answered by FCL's boolean (intersecting or separated, never an error), the
uniform families all agree, FCL misses some cylinder pairs certified touching (GJK's tolerance
decides exact contact), and families.csv counts per family exactly the failures found here by
comparing answers.jsonl with the certified answers. check_report.py checks the rest of the report
(counterexamples, page).

usage: check_plugin_fcl.py CERTCYL RESULTS_FOLDER PLUGIN SIZE"""
import collections
import ctypes
import csv
import json
import os
import subprocess
import sys

QUERIES = ("cylinder_cylinder", "triangle_cylinder")
SEPARATED, INTERSECTING = 0, 3  # certcyl/plugin.h

# A, lying along x: the axis from (0, 0, 0) to (10, 0, 0), radius 1 (x in [0, 10], y^2 + z^2 <= 1).
A = (0, 0, 0, 10, 0, 0, 1)
# (name, the other shape, answer): a cylinder along z at x = 8 (where A is only if A's centre is its
# midpoint) or a triangle in the plane z = 0.9 (inside A's wall at (8, 0, 0.9)) or z = 1.5.
BY_HAND = [
    ("cylinder_cylinder", "upright at x = 8 from z = 0.5", (8, 0, 0.5, 8, 0, 5, 0.5), INTERSECTING),
    ("cylinder_cylinder", "upright at x = 8 from z = 1.5", (8, 0, 1.5, 8, 0, 5, 0.5), SEPARATED),
    ("cylinder_cylinder", "upright at x = 11.5 from z = 0", (11.5, 0, 0, 11.5, 0, 5, 1), SEPARATED),
    ("triangle_cylinder", "triangle at z = 0.9", (7, -0.2, 0.9, 9, -0.2, 0.9, 8, 0.2, 0.9), INTERSECTING),
    ("triangle_cylinder", "triangle at z = 1.5", (7, -0.2, 1.5, 9, -0.2, 1.5, 8, 0.2, 1.5), SEPARATED),
]


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def check_plugin(path):
    """The plugin's name, after checking it and the answers BY_HAND."""
    plugin = ctypes.CDLL(path)
    plugin.certcyl_plugin_name.restype = ctypes.c_char_p
    name = plugin.certcyl_plugin_name().decode()
    if not name.startswith("fcl "):
        fail("the plugin's name %r does not start with 'fcl '" % name)
    doubles = lambda xs: (ctypes.c_double * len(xs))(*xs)
    for query, what, shape, expected in BY_HAND:
        fn = getattr(plugin, "certcyl_plugin_" + query)
        got = fn(doubles(A), doubles(shape)) if query == "cylinder_cylinder" else fn(doubles(shape), doubles(A))
        if got != expected:
            fail("%s: A and the %s: the plugin answers %d, expected %d" % (query, what, got, expected))
    return name


def main():
    certcyl, folder, plugin, size = sys.argv[1:5]
    method = check_plugin(plugin)
    cases = {}
    for query in QUERIES:
        out = subprocess.run([certcyl, "cases", "--query", query, "--size", size], capture_output=True, text=True,
                             check=True).stdout
        cases.update((c["id"], c) for c in map(json.loads, out.splitlines()))
    with open(os.path.join(folder, "answers.jsonl")) as f:
        answers = {a["id"]: a["answer"] for a in (json.loads(l) for l in f if l.strip())}
    if set(answers) != set(cases):
        fail("answers to %d cases, `certcyl cases` makes %d (%s)" %
             (len(answers), len(cases), sorted(set(answers) ^ set(cases))[:3]))
    others = sorted({a for a in answers.values()} - {"intersecting", "separated"})
    if others:
        fail("FCL's boolean answers are intersecting or separated, got %s" % others)
    # The failures, counted here: FCL says the sets meet exactly when the certified answer is not
    # separated, on the certified cases.
    failures = collections.Counter()
    missed_touching = 0
    for i, c in cases.items():
        m = c["meta"]
        if m["certified"] == "undecided":
            continue
        key = (c["query"], m["family"])
        failures[key] += 0
        if (answers[i] == "intersecting") != (m["certified"] != "separated"):
            failures[key] += 1
            missed_touching += c["query"] == "cylinder_cylinder" and m["certified"] == "touching"
    with open(os.path.join(folder, "families.csv"), newline="") as f:
        rows = {(r["query"], r["family"]): r for r in csv.DictReader(f) if r["family"] != "all"}
    if {r["method"] for r in rows.values()} != {method}:
        fail("families.csv names the methods %s, the plugin is %r" % (sorted({r["method"] for r in rows.values()}), method))
    if set(rows) != set(failures):
        fail("families.csv has rows %s, the cases' families are %s" % (sorted(rows), sorted(failures)))
    for key, n in sorted(failures.items()):
        if int(rows[key]["failures"]) != n:
            fail("families.csv counts %s failures in %s %s, the answers %d" % (rows[key]["failures"], *key, n))
        if key[1] == "uniform" and n:
            fail("FCL fails %d of the uniform %s cases, generic inputs far from contact" % (n, key[0]))
    if not missed_touching:
        fail("FCL answers every cylinder pair certified touching right: expected some misses at exact contact")
    print("ok: %s, failures per family %s, %d touching cylinder pairs missed" %
          (method, {"%s %s" % k: n for k, n in sorted(failures.items()) if n}, missed_touching))


if __name__ == "__main__":
    main()
