#!/usr/bin/env python3
"""Checks a `certcyl judge` results folder of an example: every case judged, the method fails
somewhere (the examples are naive double tests of hard cases), and the report names the failures
where they are: each family with failures has a counterexample of its own, each counterexample's
family is counted as failing in families.csv, in the printed table and in the page index.html
(its row shaded, the total of failures at the top, counterexamples drawn), and is answered by
`certcyl query` as the certified answer it records.

usage: check_report.py CERTCYL RESULTS_FOLDER METHOD"""
import csv
import json
import os
import re
import subprocess
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    certcyl, folder, method = sys.argv[1:4]
    with open(os.path.join(folder, "families.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail("families.csv has no rows")
    for r in rows:
        if r["method"] != method:
            fail("method %r, expected %r" % (r["method"], method))
    failing = {(r["query"], r["family"]) for r in rows if r["family"] != "all" and int(r["failures"]) > 0}
    cases = sum(int(r["cases"]) for r in rows if r["family"] == "all")
    summary = open(os.path.join(folder, "summary.txt")).read()
    if "%d of %d cases judged" % (cases, cases) not in summary:
        fail("not every case judged: " + summary.splitlines()[0])
    if not failing:
        fail("no failure found: the example's test is expected to fail near tangency or the caps")
    with open(os.path.join(folder, "counterexamples.jsonl")) as f:
        counterexamples = [json.loads(l) for l in f if l.strip()]
    named = {(c["query"], c["meta"]["family"]) for c in counterexamples}
    if named != failing:
        fail("families failing %s, with counterexamples %s" % (sorted(failing), sorted(named)))
    table = summary.splitlines()
    for query, family in failing:
        line = [l for l in table if l.split()[:2] == [query, family]]
        if len(line) != 1 or int(line[0].split()[4]) + int(line[0].split()[5]) == 0:
            fail("the table does not show the failures of %s %s" % (query, family))
    # The page: the failures counted at the top, each family's row shaded where it fails,
    # min(5, counterexamples) drawn.
    page = open(os.path.join(folder, "index.html"), encoding="utf-8").read()
    total = sum(int(r["failures"]) for r in rows if r["family"] == "all")
    if '<p id="verdict"><b>%d failure' % total not in page:
        fail("index.html does not open on the %d failures" % total)
    for query, family in failing:
        section = page[page.index('<h3 id="family-%s">' % query):]
        if '<tr class="wrong"><td>%s</td>' % family not in section[:section.index("</table>")]:
            fail("index.html does not shade the row of %s %s" % (query, family))
    drawn = re.findall(r'<figure class="counterexample" id="cx-\d+" data-id="([^"]*)"', page)
    if len(drawn) != min(5, len(counterexamples)) or not set(drawn) <= {c["id"] for c in counterexamples}:
        fail("index.html draws %s of %d counterexamples" % (drawn, len(counterexamples)))
    # A counterexample is a ready-to-run query line: certcyl answers it with the certified answer.
    lines = "".join(json.dumps(c) + "\n" for c in counterexamples)
    out = subprocess.run([certcyl, "query"], input=lines, capture_output=True, text=True, check=True).stdout
    for c, a in zip(counterexamples, out.splitlines()):
        a = json.loads(a)
        if a["answer"] != c["meta"]["certified"] or a["answer"] == c["meta"]["answer"]:
            fail("counterexample %s: certcyl answers %s, recorded %s, the method %s" %
                 (c["id"], a["answer"], c["meta"]["certified"], c["meta"]["answer"]))
    print("ok: %d cases, failures in %s, %d counterexamples" % (cases, sorted(failing), len(counterexamples)))


if __name__ == "__main__":
    main()
