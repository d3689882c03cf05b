#!/usr/bin/python3
"""Checks `experiments/plot_study.py --judged`: a judged method's point on the study's
speed-against-error figures (pareto, pareto_compact), from a speed.csv written here by hand.

    /usr/bin/python3 tests/report/check_plot_judged.py STUDY_DIR WORK_DIR

STUDY_DIR is the results folder of a study (summary.csv, instances.csv, summary_families.csv,
failure_maps/), e.g. the one `ctest -R report` writes; WORK_DIR is emptied and written to.
The judged method's name holds a comma and double quotes (quoted as RFC 4180 in speed.csv) and
is longer than the 30 characters a figure shows. Fails (exit status 1, one line per problem) when
  - plot_study.py --judged exits non-zero, or does not write pareto and pareto_compact (PNG, PDF);
  - a caption of index.html for those figures lacks the method's name (HTML-escaped in the page)
    or the caveat that a judged time is a mean per query over the judge's cases, not the study's
    median per instance, or that judged points are kept out of the Pareto front;
  - manifest.json does not list the speed.csv read, with its SHA-256;
  - drawn again in process (the module imported, its figures kept instead of saved), a panel
    does not hold the judged star exactly at (mean_ns, rate), rate 0 drawn at the floor 1e-4, or
    a panel of a query the method was not judged on holds one, or the star enters the Pareto
    staircase (it is faster than every method, so it would), or the legend and the panel lack
    its shortened name;
  - a malformed speed.csv (a field with an unquoted comma, no mean_ns column, a mean_ns that is
    not a number) or a folder without speed.csv does not give a non-zero exit, an error line on
    standard error naming the file and no traceback, before any figure is written.
Exit status 77 (skipped) when /usr/bin/python3 has no matplotlib.
"""
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
from html import escape
from html.parser import HTMLParser

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
PLOT = os.path.join(SOURCE, "experiments", "plot_study.py")

HEADER = "query,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,invalid,disagreement_rate,mean_ns\n"
METHOD = 'acme "fast", v2 of the intersection test'
# The name on the figures: its first 30 characters and an ellipsis.
SHOWN = 'acme "fast", v2 of the interse\u2026'
MEAN_NS = 1.5  # faster than any method of a study: on the front, were it let in
# The judged queries, their rate in speed.csv and the height it is drawn at (0 at the floor 1e-4).
JUDGED = {"line_cylinder": ("0", 1e-4), "cylinder_cylinder": ("0.25", 0.25)}
SPEED = HEADER + "".join(f'{q},"acme ""fast"", v2 of the intersection test",judged,30,1,2,0,0,0,0,{rate},1.5\n'
                         for q, (rate, _) in JUDGED.items())
CAVEATS = ("its time is its mean per query over the judge's cases", "not the study's median per instance",
           "kept out of the Pareto front")
MALFORMED = {
    "unquoted_comma": HEADER + "line_cylinder,acme, v2,judged,30,1,2,0,0,0,0,0,1.5\n",
    "no_mean_ns": HEADER.replace(",mean_ns", ",median_ns") + "line_cylinder,acme,judged,30,1,2,0,0,0,0,0,1.5\n",
    "mean_not_a_number": HEADER + "line_cylinder,acme,judged,30,1,2,0,0,0,0,0,fast\n",
}


class Captions(HTMLParser):
    """The text of every <figure id=...>'s <figcaption>, entities resolved."""

    def __init__(self):
        super().__init__()
        self.captions = {}
        self._figure = None
        self._text = None

    def handle_starttag(self, tag, attrs):
        if tag == "figure":
            self._figure = dict(attrs).get("id")
        elif tag == "figcaption":
            self._text = []

    def handle_endtag(self, tag):
        if tag == "figcaption" and self._text is not None:
            self.captions[self._figure] = "".join(self._text)
            self._text = None

    def handle_data(self, data):
        if self._text is not None:
            self._text.append(data)


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def run(args):
    return subprocess.run(["/usr/bin/python3", PLOT] + args, capture_output=True, text=True)


def check_run(study, work, judge_dir, problems):
    """plot_study.py --judged judge_dir into work/out: its figures, captions and manifest."""
    out = os.path.join(work, "out")
    r = run([study, "--out", out, "--judged", judge_dir])
    if r.returncode != 0:
        problems.append(f"plot_study.py --judged exited {r.returncode}: {r.stderr.strip()[-2000:]}")
        return
    for name in ("pareto", "pareto_compact"):
        for ext in ("png", "pdf"):
            if not os.path.isfile(os.path.join(out, f"{name}.{ext}")):
                problems.append(f"{name}.{ext} not written")
    with open(os.path.join(out, "index.html"), encoding="utf-8") as f:
        html = f.read()
    page = Captions()
    page.feed(html)
    for name in ("pareto", "pareto_compact"):
        caption = page.captions.get(name)
        if caption is None:
            problems.append(f"index.html has no caption for {name}")
            continue
        if METHOD not in caption:
            problems.append(f"{name}'s caption does not name the judged method {METHOD!r}: {caption!r}")
        for c in CAVEATS:
            if c not in caption:
                problems.append(f"{name}'s caption lacks {c!r}: {caption!r}")
    if escape(METHOD) not in html:
        problems.append(f"index.html does not hold the method's name HTML-escaped ({escape(METHOD)})")
    with open(os.path.join(out, "manifest.json")) as f:
        inputs = json.load(f)["inputs"]
    speed = os.path.join(judge_dir, "speed.csv")
    key = os.path.relpath(speed, study)
    if inputs.get(key) != sha256(speed):
        problems.append(f"manifest.json inputs: {key} -> {inputs.get(key)}, expected {sha256(speed)}")


def check_drawing(study, work, judge_dir, problems):
    """Draws pareto and pareto_compact in process, the figures kept, and reads the points back."""
    sys.path.insert(0, os.path.join(SOURCE, "experiments"))
    import plot_study as ps
    from certcyl_results import QUERY_TITLES, read_csv

    kept = {}

    def keep(fig, out, name, caption, **kwargs):
        kept[name] = fig

    ps.save = keep
    judged = ps.read_judged([judge_dir])
    rows = read_csv(os.path.join(study, "instances.csv"))
    summary = read_csv(os.path.join(study, "summary.csv"))
    studied = {r["query"] for r in summary}
    ps.pareto(rows, summary, work, judged)
    ps.pareto_compact(rows, summary, work, judged)
    for name in ("pareto", "pareto_compact"):
        fig = kept.get(name)
        if fig is None:
            problems.append(f"{name}: not drawn")
            continue
        legend = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
        if "judged: " + SHOWN not in legend:
            problems.append(f"{name}: no legend entry 'judged: {SHOWN}' in {legend}")
        titles = {QUERY_TITLES[q]: q for q in QUERY_TITLES}
        seen = set()
        for ax in fig.axes:
            q = titles.get(re.sub(r" \(\d+ paired\)$", "", ax.get_title()))  # the panel counts its paired instances
            if q is None:
                continue
            seen.add(q)
            stars = [tuple(map(float, p)) for c in ax.collections if c.get_gid() == "judged" for p in c.get_offsets()]
            want = [(MEAN_NS, JUDGED[q][1])] if q in JUDGED else []
            if stars != want:
                problems.append(f"{name}, {q}: judged points {stars}, expected {want}")
            steps = [x for line in ax.get_lines() if line.get_drawstyle() == "steps-post" for x in line.get_xdata()]
            if any(float(x) == MEAN_NS for x in steps):
                problems.append(f"{name}, {q}: the judged point is on the Pareto staircase {steps}")
            if q in JUDGED and SHOWN not in [t.get_text() for t in ax.texts]:
                problems.append(f"{name}, {q}: the panel does not name the judged point {SHOWN!r}")
        for q in JUDGED:
            if q in studied and q not in seen:
                problems.append(f"{name}: no panel for {q}")


def check_malformed(study, work, problems):
    cases = dict(MALFORMED, no_speed_csv=None)
    for case, text in cases.items():
        d = os.path.join(work, "malformed", case)
        os.makedirs(d)
        speed = os.path.join(d, "speed.csv")
        if text is not None:
            with open(speed, "w", newline="") as f:
                f.write(text)
        out = os.path.join(d, "out")
        r = run([study, "--out", out, "--judged", d])
        if r.returncode == 0:
            problems.append(f"{case}: plot_study.py exited 0")
        if "Traceback" in r.stderr:
            problems.append(f"{case}: a traceback instead of an error line: {r.stderr.strip()[-500:]}")
        if not any(speed in line and "plot_study" in line for line in r.stderr.splitlines()):
            problems.append(f"{case}: no error line naming {speed} on standard error: {r.stderr.strip()!r}")
        if os.path.exists(os.path.join(out, "pareto.png")):
            problems.append(f"{case}: figures written despite the error")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    study, work = sys.argv[1:]
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError:
        print("skipped: /usr/bin/python3 has no matplotlib (bash scripts/install-deps.sh --study)")
        return 77
    if not os.path.isfile(os.path.join(study, "summary.csv")):
        print(f"check_plot_judged: {study}: no summary.csv (not a study's results folder)")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    judge_dir = os.path.join(work, "judge")
    os.makedirs(judge_dir)
    with open(os.path.join(judge_dir, "speed.csv"), "w", newline="") as f:
        f.write(SPEED)
    problems = []
    check_malformed(study, work, problems)
    check_drawing(study, os.path.join(work, "drawn"), judge_dir, problems)
    check_run(study, work, judge_dir, problems)
    for p in problems:
        print(f"check_plot_judged: {p}")
    print(f"check_plot_judged: {study}: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
