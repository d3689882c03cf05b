#!/usr/bin/python3
"""Checks the page `certcyl judge` writes, RESULTS_DIR/index.html, against the folder's own data
files (families.csv, counterexamples.jsonl) and, when given, as Chromium rendered it.

    /usr/bin/python3 tests/report/check_judge_report.py RESULTS_DIR [SCREENSHOT.png DOM.html]

Fails (exit status 1, one line per problem) when
  - index.html holds a script, an <img>, an external resource (http:, https:, //) or a link to
    a file that does not exist, or its style loads a resource;
  - the verdict at the top does not state the failures and certified cases of families.csv's
    "all" rows, or the family tables do not hold exactly families.csv's rows, each with its
    false positives and negatives, its failure rate and the 95% Wilson interval computed here,
    shaded when it has a failure;
  - the page does not show min(5, counterexamples) figures, each of a distinct counterexample of
    counterexamples.jsonl with its certified answer and the method's, each with two inline SVG
    views drawing the cylinder (blue) and the other operand (red); or the figures do not cover
    min(5, failing families) families, each with its family's largest |gap|;
  - the DOM Chromium rendered lacks the figures' SVG views;
  - the screenshot is blank, or does not show one band of blue and red drawing per figure.
"""
import csv
import json
import math
import os
import re
import sys
from html.parser import HTMLParser

# The 95% Wilson score interval, from the module the study's scripts share (an implementation
# independent of the C++ one that wrote the page).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "experiments"))
from certcyl_results import wilson  # noqa: E402

BLUE = (0x1f, 0x77, 0xb4)
RED = (0xd6, 0x27, 0x28)


class Page(HTMLParser):
    """The page's tags in order, its family tables' rows and its counterexample figures."""

    def __init__(self):
        super().__init__()
        self.tags = []  # (tag, attrs)
        self.rows = []  # {"query", "classes", "cells": [text]}
        self.figures = []  # {"id", "svgs": [{"shapes", "red"}], "cells": {class: text}}
        self.verdict = None
        self._query = None
        self._row = None
        self._cell = None
        self._figure = None
        self._svg = None
        self._verdict = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.append((tag, a))
        if tag == "h3" and a.get("id", "").startswith("family-"):
            self._query = a["id"][len("family-"):]
        elif tag == "tr" and self._query is not None and self._figure is None:
            self._row = {"query": self._query, "classes": (a.get("class") or "").split(), "cells": []}
        elif tag == "td" and self._row is not None:
            self._row["cells"].append("")
            self._cell = "row"
        elif tag == "figure" and a.get("class") == "counterexample":
            self._figure = {"id": a.get("data-id"), "svgs": [], "cells": {}}
        elif tag == "svg" and self._figure is not None:
            self._svg = {"shapes": 0, "red": 0}
        elif self._svg is not None and tag in ("polygon", "polyline", "line", "circle", "path"):
            self._svg["shapes"] += 1
            if RED_HEX in (a.get("stroke", "").lower(), a.get("fill", "").lower()):
                self._svg["red"] += 1
        elif tag == "td" and self._figure is not None and a.get("class"):
            self._figure["cells"][a["class"]] = ""
            self._cell = a["class"]
        elif tag == "p" and a.get("id") == "verdict":
            self._verdict = ""

    def handle_endtag(self, tag):
        if tag == "td":
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.rows.append(self._row)
            self._row = None
        elif tag == "table" and self._figure is None:
            self._query = None
        elif tag == "svg" and self._svg is not None:
            self._figure["svgs"].append(self._svg)
            self._svg = None
        elif tag == "figure" and self._figure is not None:
            self.figures.append(self._figure)
            self._figure = None
        elif tag == "p" and self._verdict is not None:
            self.verdict = self._verdict
            self._verdict = None

    def handle_data(self, data):
        if self._cell == "row" and self._row is not None:
            self._row["cells"][-1] += data
        elif self._cell and self._figure is not None:
            self._figure["cells"][self._cell] += data
        if self._verdict is not None:
            self._verdict += data


RED_HEX = "#%02x%02x%02x" % RED


def pct(p):
    return "%.1f%%" % (100 * p)


def gap_size(c):
    g = c["meta"]["gap"]
    return math.inf if g is None else abs(0.5 * g[0] + 0.5 * g[1])


def check_page(folder, problems):
    with open(os.path.join(folder, "index.html"), encoding="utf-8") as f:
        text = f.read()
    page = Page()
    page.feed(text)

    for tag, a in page.tags:
        if tag in ("script", "iframe", "object", "embed", "img", "link"):
            problems.append(f"index.html holds a <{tag}>")
        for key in ("src", "href"):
            ref = a.get(key)
            if ref is None or ref.startswith("#"):
                continue
            if re.match(r"^([a-z]+:|//)", ref):
                problems.append(f"index.html refers to an external resource: {ref}")
            elif not os.path.exists(os.path.join(folder, ref)):
                problems.append(f"index.html refers to a missing file: {ref}")
    if re.search(r"url\(|@import", text):
        problems.append("index.html's style loads a resource")

    with open(os.path.join(folder, "families.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    totals = [r for r in rows if r["family"] == "all"]
    failures = sum(int(r["failures"]) for r in totals)
    certified = sum(int(r["cases"]) - int(r["uncertified"]) for r in totals)
    verdict = " ".join((page.verdict or "").split())
    if not verdict.startswith(f"{failures} failure") or f"among the {certified} certified cases" not in verdict:
        problems.append(f"the verdict '{verdict}' does not state {failures} failures among {certified} certified cases")

    # The family tables: query, family, configuration, cases, certified, FP, FN, other, rate, interval.
    shown = {(r["query"], r["cells"][0].strip()): r for r in page.rows if r["cells"]}
    expected = {(r["query"], r["family"]): r for r in rows}
    if sorted(shown) != sorted(expected):
        problems.append(f"family tables: {len(shown)} rows for {len(expected)} in families.csv "
                        f"(missing {sorted(set(expected) - set(shown))[:3]}, unexpected {sorted(set(shown) - set(expected))[:3]})")
    for key in sorted(set(shown) & set(expected)):
        cells = [c.strip() for c in shown[key]["cells"]]
        r = expected[key]
        n = int(r["cases"]) - int(r["uncertified"])
        fails = int(r["false_positive"]) + int(r["false_negative"])
        want = [r["cases"], str(n), r["false_positive"], r["false_negative"]]
        if cells[2:6] != want:
            problems.append(f"{key}: cases, certified, FP, FN shown {cells[2:6]}, families.csv {want}")
        if n > 0:
            lo, hi = wilson(fails, n)
            if cells[7] != pct(fails / n) or cells[8] != f"{pct(lo)} to {pct(hi)}":
                problems.append(f"{key}: rate '{cells[7]}', interval '{cells[8]}'; expected {pct(fails / n)}, {pct(lo)} to {pct(hi)}")
        if ("wrong" in shown[key]["classes"]) != (fails > 0):
            problems.append(f"{key}: {fails} failures but the row is {'' if 'wrong' in shown[key]['classes'] else 'not '}shaded")

    # The counterexamples: min(5, all), distinct, their answers, drawn, the families covered.
    with open(os.path.join(folder, "counterexamples.jsonl")) as f:
        cx = {c["id"]: c for c in (json.loads(l) for l in f if l.strip())}
    figures = page.figures
    if len(figures) != min(5, len(cx)):
        problems.append(f"{len(figures)} counterexample figures for {len(cx)} counterexamples (expected {min(5, len(cx))})")
    ids = [fig["id"] for fig in figures]
    if len(set(ids)) != len(ids):
        problems.append(f"a counterexample is shown twice: {ids}")
    for fig in figures:
        c = cx.get(fig["id"])
        if c is None:
            problems.append(f"figure {fig['id']} is no counterexample of counterexamples.jsonl")
            continue
        cells = {k: v.strip() for k, v in fig["cells"].items()}
        if cells.get("certified") != c["meta"]["certified"] or cells.get("answer") != c["meta"]["answer"]:
            problems.append(f"figure {fig['id']}: answers {cells.get('certified')}/{cells.get('answer')}, "
                            f"recorded {c['meta']['certified']}/{c['meta']['answer']}")
        if len(fig["svgs"]) != 2 or any(s["shapes"] < 2 or s["red"] < 1 for s in fig["svgs"]):
            problems.append(f"figure {fig['id']}: not two SVG views with the cylinder and a red operand: {fig['svgs']}")
    families = {(c["query"], c["meta"]["family"]) for c in cx.values()}
    first = [cx[i] for i in ids[:min(5, len(families))] if i in cx]
    covered = {(c["query"], c["meta"]["family"]) for c in first}
    if len(covered) != len(first):
        problems.append(f"the first {len(first)} figures repeat a family while {len(families)} families fail")
    for c in first:
        clearest = max(gap_size(d) for d in cx.values() if (d["query"], d["meta"]["family"]) == (c["query"], c["meta"]["family"]))
        if gap_size(c) != clearest:
            problems.append(f"figure {c['id']}: |gap| {gap_size(c)}, not its family's largest ({clearest})")
    return len(figures)


class Dom(HTMLParser):
    """Counts the <svg> elements inside the counterexample figures of a rendered DOM."""

    def __init__(self):
        super().__init__()
        self.svgs = 0
        self.depth = 0

    def handle_starttag(self, tag, attrs):
        if tag == "figure" and dict(attrs).get("class") == "counterexample":
            self.depth += 1
        elif tag == "svg" and self.depth:
            self.svgs += 1

    def handle_endtag(self, tag):
        if tag == "figure" and self.depth:
            self.depth -= 1


def check_screenshot(path, figures, problems):
    """Not blank; one band of rows holding the blue and the red of a drawing per figure (a band:
    rows with drawing pixels less than 30 rows apart, at least 40 rows tall, with 150 blue and
    30 red pixels; the colour key in the text is smaller)."""
    import matplotlib.image
    import numpy as np

    rgb = np.round(matplotlib.image.imread(path)[:, :, :3] * 255).astype(int)
    height, width = rgb.shape[:2]
    colours = np.unique((rgb[:, :, 0] << 16) | (rgb[:, :, 1] << 8) | rgb[:, :, 2])
    share = float(np.mean(np.any(rgb != 255, axis=2)))
    if len(colours) < 20 or share < 0.01:
        problems.append(f"{path}: blank ({len(colours)} colours, {100 * share:.2f}% of the pixels not white)")
    blue = np.sum(np.all(np.abs(rgb - np.array(BLUE)) <= 12, axis=2), axis=1)
    red = np.sum(np.all(np.abs(rgb - np.array(RED)) <= 12, axis=2), axis=1)
    drawn = np.nonzero(blue + red)[0]
    bands = []
    for y in drawn:
        if bands and y - bands[-1][1] < 30:
            bands[-1][1] = y
        else:
            bands.append([y, y])
    shown = [(a, b) for a, b in bands if b - a >= 40 and blue[a:b + 1].sum() >= 150 and red[a:b + 1].sum() >= 30]
    print(f"check_judge_report: {os.path.basename(path)}: {width}x{height}, {len(colours)} colours, {100 * share:.1f}% not white, "
          f"drawings in rows {shown}")
    if len(shown) != figures:
        problems.append(f"{path}: {len(shown)} bands of drawing for {figures} figures")


def main():
    if len(sys.argv) not in (2, 4):
        print(__doc__)
        return 2
    folder = sys.argv[1]
    problems = []
    figures = check_page(folder, problems)
    if len(sys.argv) == 4:
        shot, dom_file = sys.argv[2:]
        dom = Dom()
        with open(dom_file, encoding="utf-8", errors="replace") as f:
            dom.feed(f.read())
        if dom.svgs != 2 * figures:
            problems.append(f"the rendered DOM holds {dom.svgs} SVG views in the figures, expected {2 * figures}")
        check_screenshot(shot, figures, problems)
    for p in problems:
        print(f"check_judge_report: {p}")
    print(f"check_judge_report: {folder}: {figures} figures, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
