#!/usr/bin/python3
"""Tables and quoted numbers of the paper, generated from a results folder of `certcyl study`.

    /usr/bin/python3 paper/make_tables.py RESULTS_DIR OUT_DIR

Reads the study's CSV files (instances.csv, inputs.csv, summary.csv, summary_families.csv,
hunt.csv, timing.csv, timing_stages.csv, timing_thread.csv, uniform.csv, failure_maps/*.csv), Core_Diagnostics
when the study wrote one, and machine.json (the run's description: compiler, CPU,
libraries), nothing else, and writes into OUT_DIR:
  numbers.tex     one \\newcommand per quoted number, named \\csname stat:KEY\\endcsname and
                  read in the text through \\stat{KEY} (paper.tex makes an unknown key an error)
  units.json      the unit of every quoted count (instances, answers, searches, methods, cells),
                  null for another number
  tables/*.tex    the tables the paper \\input's
  manifest.json   the SHA-256 of every file read (relative to RESULTS_DIR) and of every file
                  written (relative to OUT_DIR); paper/check_paper.py compares it with the study
Nothing here is typed by hand from a study: every number comes from those files.
"""
import json
import math
import os
import sys
from collections import Counter, defaultdict

# The helpers the scripts of experiments/ and paper/ share (reading CSV files and recording them
# for the manifest, SHA-256, medians and percentiles).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments"))
import certcyl_results as cr  # noqa: E402
from certcyl_results import fnum, note_read, percentile, read_csv, upper_median, write_manifest  # noqa: E402

WRITTEN = []


def write(out, rel, text):
    path = os.path.join(out, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    WRITTEN.append(path)


# ---- formatting ------------------------------------------------------------------------------

def tex_escape(s):
    out = []
    for c in str(s):
        if c in "_&%$#{}":
            out.append("\\" + c)
        elif c == "<":
            out.append("$<$")
        elif c == ">":
            out.append("$>$")
        elif c == "~":
            out.append("\\~{}")
        elif c == "^":
            out.append("\\^{}")
        elif c == "\\":
            out.append("$\\backslash$")
        else:
            out.append(c)
    return "".join(out)


def sci(x, digits=2):
    """x in scientific notation for LaTeX text: 0, 3.4e-2 as $3.4\\cdot10^{-2}$, or plain when 0.01 <= |x| < 1000."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "--"
    if x == 0:
        return "0"
    if isinstance(x, float) and math.isinf(x):
        return "$\\infty$" if x > 0 else "$-\\infty$"
    e = math.floor(math.log10(abs(x)))
    m = round(x / 10 ** e, digits - 1)
    if abs(m) >= 10:
        m /= 10
        e += 1
    if -2 <= e <= 2:
        v = f"{x:.{max(0, digits - 1 - e)}f}"
        return f"${v}$" if x < 0 else v
    ms = f"{m:.{digits - 1}f}"
    if ms.rstrip("0").rstrip(".") == "1":
        return f"$10^{{{e}}}$" if m > 0 else f"$-10^{{{e}}}$"
    return f"${ms}\\cdot 10^{{{e}}}$"


def sci_down(x, digits=2):
    """sci(x) of a lower bound x >= 0, its significant digits rounded down (toward 0), so that
    "|G| >= sci_down(x)" stays true: 3.47 reads 3.4, not 3.5."""
    if x is None or not math.isfinite(x) or x <= 0:
        return sci(x, digits)
    e = math.floor(math.log10(x)) - (digits - 1)
    m = math.floor(x / 10 ** e)
    while m * 10 ** e > x:  # the division's rounding, either way
        m -= 1
    while (m + 1) * 10 ** e <= x:
        m += 1
    return sci(m * 10 ** e, digits)


def ns_text(ns):
    return cr.ns_tex(ns)


def pct(a, b):
    return f"{100.0 * a / b:.1f}\\,\\%" if b else "--"


def pct_rate(r):
    """A rate in percent for a table cell, two significant digits; a dash for None (no
    three-valued error: a Boolean method)."""
    if r is None or (isinstance(r, float) and math.isnan(r)):
        return "--"
    return cr.percent_text(r)


def wilson_pct(k, n):
    """The 95% Wilson interval of k wrong in n decided, in percent: "0.41--0.52"."""
    lo, hi = cr.error_interval(k, n)
    return f"{cr.percent_text(lo)}--{cr.percent_text(hi)}"


def method_tex(m):
    """A method name for tables: algorithm in roman, number type in typewriter."""
    base, _, nt = m.partition("/")
    return f"{tex_escape(base)}\\,/\\,\\texttt{{{tex_escape(nt)}}}"


def hexfloat_tex(s):
    return "\\texttt{" + tex_escape(s) + "}"


# ---- the numbers file --------------------------------------------------------------------------

class Numbers:
    def __init__(self):
        self.values = {}

    def __setitem__(self, key, value):
        if key in self.values and self.values[key] != value:
            raise RuntimeError(f"number {key} defined twice with different values")
        self.values[key] = value

    def text(self):
        lines = ["% Generated by paper/make_tables.py from the study's CSV files: do not edit.",
                 "% Read in the text as \\stat{KEY}."]
        for k in sorted(self.values):
            if any(c in k for c in "{}\\%#"):
                raise RuntimeError(f"bad key {k}")
            lines.append(f"\\expandafter\\newcommand\\csname stat:{k}\\endcsname{{{self.values[k]}}}")
        return "\n".join(lines) + "\n"


# The unit of a quoted count, by the first fields of its key (the longest rule that matches
# wins): what it counts, so that paper/check_paper.py can refuse "A of B" in the text where A and
# B count different things (searches against methods, answers against instances). Written to
# units.json for every key (null for a number that is not a count).
COUNT_UNITS = {
    "inst": "instances", "check:constructed": "instances", "check:undecided": "instances", "stagecount": "instances",
    "paired": "instances", "timingpaired": "instances", "terr:paired": "instances",
    "inst:maxk": None, "inst:families": "families", "inst:familyquery": "families",
    "check:construction": "answers", "check:gapsign": "answers",
    "n": "answers", "fp": "answers", "fn": "answers", "cls": "answers", "wrong": "answers", "wrong3": "answers",
    "undec": "answers", "err": "answers", "fntouch": "answers", "conv": "answers", "alg": "answers",
    "unsplit": "answers", "cdiff": "answers", "split": "answers", "kwrong": "answers", "kn": "answers",
    "famn": "answers", "famfp": "answers", "famfn": "answers", "famwrong": "answers", "famcls": "answers",
    "pn": "answers", "pfp": "answers", "pfn": "answers", "pcls": "answers",
    "udecided": "answers", "ufp": "answers", "ufn": "answers", "ucls": "answers",
    "hunt:searches": "searches", "hunt:found": "searches", "hunt:methodswrong": "methods", "hunt:methodcount": "methods",
    "map": "cells", "map3": "cells", "mapcls": "cells", "mapundec": "cells", "core": "warnings",
}


def count_unit(key):
    """The unit of COUNT_UNITS of a number's key, or None (not a count, or not one the rules
    name): the rule of its first two fields before that of its first."""
    fields = key.split(":")
    two = ":".join(fields[:2])
    return COUNT_UNITS[two] if two in COUNT_UNITS else COUNT_UNITS.get(fields[0])


# ---- aggregation ------------------------------------------------------------------------------

class Tally(cr.Tally):
    """cr.Tally (a method's rows: n, the outcomes, the times) with what the tables add: the
    queries, the kind, whether the method is Boolean (answered `intersecting`: no three-valued
    error), its Boolean errors by cause, its contract and the instances where that differs."""

    __slots__ = ("conv", "alg", "unsplit", "cdiff", "contract", "converts", "queries", "kind", "boolean")

    def __init__(self):
        super().__init__()
        # Boolean errors (FP + FN) by cause (instances.csv's cause: each is conversion, algorithm
        # or unsplit), and the instances whose answer under the method's contract is not the solid
        # one.
        self.conv = self.alg = self.unsplit = self.cdiff = 0
        self.contract = "solid"
        self.converts = False
        self.queries = set()
        self.kind = ""
        self.boolean = False

    def add(self, r):
        self.kind = r["kind"]
        self.queries.add(r["query"])
        if r["outcome"] == "uncertified":
            return
        super().add(r)
        self.boolean |= r["answer"] == "intersecting"
        if r["outcome"] in cr.FAILURES:
            self.conv += r["cause"] in ("conversion", "conversion+algorithm")
            self.alg += r["cause"] in ("algorithm", "conversion+algorithm")
            self.unsplit += r["cause"] == "unsplit"
        meets = ("touching", "overlapping")
        self.cdiff += (r["contract_answer"] in meets) != (r["certified_answer"] in meets)
        if r["contract"] != "solid":
            self.contract = r["contract"]
        self.converts |= r["received_answer"] != ""

    fp = property(lambda self: self.errors.fp)
    fn = property(lambda self: self.errors.fn)
    cls = property(lambda self: self.errors.cls)
    decided = property(lambda self: self.errors.decided)

    @property
    def rate(self):
        """The Boolean error rate, (FP + FN) / decided (summary.csv's disagreement_rate); 0 when
        nothing was decided."""
        return self.errors.rate if self.decided else 0.0

    @property
    def rate3(self):
        """The three-valued error rate, (FP + FN + class) / decided; None for a Boolean method."""
        if self.boolean:
            return None
        return self.errors.rate3 if self.decided else 0.0


# The numbers a Tally gives the text, by key prefix: N[f"{prefix}:{key}"] (tally_numbers).
TALLY_NUMBERS = {
    "n": lambda t: str(t.n), "fp": lambda t: str(t.fp), "fn": lambda t: str(t.fn), "cls": lambda t: str(t.cls),
    "wrong": lambda t: str(t.fp + t.fn), "wrong3": lambda t: str(t.fp + t.fn + t.cls),
    "undec": lambda t: str(t.undecided), "err": lambda t: str(t.error),
    "rate": lambda t: sci(t.rate), "rate3": lambda t: sci(t.rate3),
    "conv": lambda t: str(t.conv), "alg": lambda t: str(t.alg), "unsplit": lambda t: str(t.unsplit), "cdiff": lambda t: str(t.cdiff),
}


def tally_numbers(N, key, t, names, prefix=""):
    """N[f"{prefix}{name}:{key}"] for every name of `names` (keys of TALLY_NUMBERS) of Tally t."""
    for name in names:
        N[f"{prefix}{name}:{key}"] = TALLY_NUMBERS[name](t)


def gap_bound(r):
    """The certified lower bound of the size of a row's signed gap (0 when its enclosure
    [gap_lo, gap_hi] contains 0)."""
    lo, hi = fnum(r["gap_lo"]), fnum(r["gap_hi"])
    return 0.0 if lo <= 0 <= hi else min(abs(lo), abs(hi))


SEED_BASES = [
    ("shene", "Shene (corrected)"),
    ("gullotti_as_written", "Gullotti, as written"),
    ("gullotti", "Gullotti, corrected"),
    ("eberly_triangle", "Eberly, triangle"),
    ("eberly_cylinders_as_written", "Eberly, cyl., as written"),
    ("eberly_cylinders", "Eberly, cyl., corrected"),
]
NTS = [("double", "double"), ("long_double", "long dbl."), ("interval", "interval"),
       ("gmpfr<24>", "MPFR 24"), ("gmpfr<53>", "MPFR 53"), ("gmpfr<113>", "MPFR 113"),
       ("gmpfr<256>", "MPFR 256"), ("core_expr", "CORE")]
HUNT_ROWS = 18
# The methods of the table of errors against k (tables/error_by_k.tex), per query: those the
# results section discusses, in the order shown; a method the study did not run is left out.
K_TABLE_METHODS = [
    ("line_cylinder", ["robust/double", "shene/double", "gullotti/double", "shene/long_double"]),
    ("ray_cylinder", ["shene/double", "bullet/float"]),
    ("segment_cylinder", ["shene/double"]),
    ("line_elliptic_cylinder", ["gullotti_as_written/double", "gullotti/double"]),
    ("triangle_cylinder", ["eberly_triangle/double", "ode_mesh/double"]),
    ("cylinder_cylinder", ["eberly_cylinders_as_written/double", "eberly_cylinders/double", "fcl/double", "bullet/float"]),
]
QUERY_TEX = {
    "line_cylinder": "line", "ray_cylinder": "ray", "segment_cylinder": "segment",
    "line_elliptic_cylinder": "line/elliptic", "triangle_cylinder": "triangle",
    "cylinder_cylinder": "cylinder pair",
}


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    res, out = sys.argv[1], sys.argv[2]
    os.makedirs(os.path.join(out, "tables"), exist_ok=True)
    N = Numbers()

    rows = read_csv(os.path.join(res, "instances.csv"))
    inputs = read_csv(os.path.join(res, "inputs.csv"))
    summary = read_csv(os.path.join(res, "summary.csv"))
    families = read_csv(os.path.join(res, "summary_families.csv"))
    hunt = read_csv(os.path.join(res, "hunt.csv"))
    timing = read_csv(os.path.join(res, "timing.csv"))
    timing_stages = read_csv(os.path.join(res, "timing_stages.csv"))
    timing_thread = read_csv(os.path.join(res, "timing_thread.csv"))
    mpath = os.path.join(res, "machine.json")
    note_read(mpath)
    with open(mpath) as f:
        machine = json.load(f)

    # ---- the run ----
    N["machine:cpu"] = tex_escape(machine.get("cpu", "unknown"))
    N["machine:threads"] = str(machine.get("hardware_threads", "?"))
    N["machine:compiler"] = tex_escape(machine.get("compiler", "unknown").split(" (")[0])
    N["machine:flags"] = "\\texttt{" + tex_escape(machine.get("flags", "")) + "}"
    N["machine:cgal"] = tex_escape(machine.get("cgal", "?"))
    N["machine:commit"] = "\\texttt{" + tex_escape(str(machine.get("commit", "?"))[:12]) + "}"
    N["machine:peers"] = tex_escape(", ".join(machine.get("peers", [])) or "none")
    opts = machine.get("options", {})
    N["run:size"] = tex_escape(str(opts.get("size", "?")))
    N["run:seed"] = tex_escape(str(opts.get("seed", "?")))
    N["run:perfamily"] = str(opts.get("per_family", "?"))
    N["run:mapcells"] = str(opts.get("map_cells", "?"))
    N["run:mapstep"] = str(opts.get("map_step", "?"))
    N["run:hunt"] = str(opts.get("hunt_evaluations", "?"))
    N["run:date"] = tex_escape(str(machine.get("date", "?"))[:10])

    # ---- instances and checks (inputs.csv) ----
    N["inst:total"] = str(len(inputs))
    per_query = Counter(r["query"] for r in inputs)
    for q, n in per_query.items():
        N[f"inst:{q}"] = str(n)
    fams = sorted({(r["query"], r["family"]) for r in inputs})
    N["inst:families"] = str(len({f for _, f in fams}))
    N["inst:familyquery"] = str(len(fams))
    known = [r for r in inputs if r["expected"] != "unknown"]
    N["check:constructed"] = str(len(known))
    N["check:undecided"] = str(sum(r["certified_answer"] == "undecided" for r in inputs))
    N["check:gapsign"] = str(sum(r["gap_sign_ok"] != "1" for r in inputs))
    N["check:construction"] = str(sum(r["expected"] != r["certified_answer"] and r["certified_answer"] != "undecided" for r in known))
    answers = Counter(r["certified_answer"] for r in inputs)
    for a in ("separated", "touching", "overlapping", "undecided"):
        N[f"inst:answer:{a}"] = str(answers.get(a, 0))
    N["inst:atdegeneracy"] = str(sum(r["k_ulps"] in ("0", "0.0") and r["family"] != "uniform" for r in inputs))
    N["inst:uniform"] = str(sum(r["family"] == "uniform" for r in inputs))
    maxk = max((abs(int(float(r["k_ulps"]))) for r in inputs if r["k_ulps"] not in ("",)), default=0)
    N["inst:maxk"] = sci(float(maxk))

    # Families table: per query, each family with its instance count and constructed count.
    by_qf = defaultdict(lambda: [0, 0, Counter()])
    for r in inputs:
        c = by_qf[(r["query"], r["family"])]
        c[0] += 1
        c[1] += r["expected"] != "unknown"
        c[2][r["certified_answer"]] += 1
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}llrrrrr@{}}", "\\toprule",
             "query & families & $n$ & constructed & sep. & touch. & overl.\\\\", "\\midrule"]
    for q in sorted(per_query, key=lambda q: list(QUERY_TEX).index(q) if q in QUERY_TEX else 99):
        fs = sorted(f for qq, f in by_qf if qq == q)
        tot = [sum(by_qf[(q, f)][0] for f in fs), sum(by_qf[(q, f)][1] for f in fs)]
        ans = Counter()
        for f in fs:
            ans.update(by_qf[(q, f)][2])
        names = ", ".join(tex_escape(f) for f in fs)
        lines.append(f"{QUERY_TEX.get(q, tex_escape(q))} & \\parbox[t]{{0.46\\textwidth}}{{\\raggedright\\footnotesize {names}}} & {tot[0]} & {tot[1]} & "
                     f"{ans.get('separated', 0)} & {ans.get('touching', 0)} & {ans.get('overlapping', 0)}\\\\[2pt]")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/families.tex", "\n".join(lines) + "\n")

    # ---- per-method tallies (instances.csv), across queries and per query ----
    tally = defaultdict(Tally)
    tally_q = defaultdict(Tally)
    terr = defaultdict(list)
    wrong_gap = defaultdict(float)  # largest certified lower bound of |G| (depth margin) among wrong answers
    fn_touching = Counter()  # false negatives on instances whose certified answer is touching
    for r in rows:
        m = r["method"]
        tally[m].add(r)
        tally_q[(r["query"], m)].add(r)
        t = fnum(r["t_error_ulps"])
        if not math.isnan(t):
            terr[(r["query"], m)].append(t)
        if r["outcome"] == "false_negative" and r["certified_answer"] == "touching":
            fn_touching[m] += 1
        # (The depth margin G only: a cylinder pair's gap, log(phi*), is another quantity.)
        if r["outcome"] in cr.FAILURES and r["query"] != "cylinder_cylinder":
            wrong_gap[m] = max(wrong_gap[m], gap_bound(r))
    N["rows:total"] = str(len(rows))
    N["methods:total"] = str(len(tally))
    for m, t in tally.items():
        tally_numbers(N, m, t, ("n", "fp", "fn", "wrong", "wrong3", "cls", "undec", "err", "rate", "rate3"))
        N[f"ns:{m}"] = ns_text(upper_median(t.ns))
        N[f"q:{m}"] = str(len(t.queries))
        N[f"maxwronggap:{m}"] = sci(wrong_gap.get(m, 0.0))
        N[f"fntouch:{m}"] = str(fn_touching.get(m, 0))
        tally_numbers(N, m, t, ("conv", "alg", "unsplit", "cdiff"))
    for (q, m), t in tally_q.items():
        tally_numbers(N, f"{q}:{m}", t, ("n", "fp", "fn", "cls", "undec", "rate", "rate3"))
        N[f"ns:{q}:{m}"] = ns_text(upper_median(t.ns))
        tally_numbers(N, f"{q}:{m}", t, ("wrong", "conv", "alg", "unsplit", "cdiff"))
    # The peers and the methods that receive a rounded instance (Bullet's floats, Gmpfr at 24
    # bits): per query, the contract, the Boolean errors split into conversion and algorithm
    # (each error is one of them: conv + alg + unsplit = wrong), and the instances where the contract differs from the
    # solid answer, judged under the contract and not counted as errors.
    CONTRACT_TEX = {"solid": "solid", "surface_entry": "entry", "surface_hit": "hit"}
    # (The peers per query; the 24-bit methods over their queries, "all".)
    split_rows = [((q, m), t) for (q, m), t in tally_q.items() if t.kind == "peer"]
    split_rows.sort(key=lambda x: (x[0][1], list(QUERY_TEX).index(x[0][0]) if x[0][0] in QUERY_TEX else 99))
    split_rows += sorted((("all", m), t) for m, t in tally.items() if t.converts and t.kind != "peer")
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}llrrrrrrr@{}}", "\\toprule",
             "method & query & contract & $n$ & wrong & conv. & alg. & unsplit & contract differs\\\\", "\\midrule"]
    for (q, m), t in split_rows:
        lines.append(f"{method_tex(m)} & {QUERY_TEX.get(q, tex_escape(q))} & {CONTRACT_TEX.get(t.contract, tex_escape(t.contract))} & "
                     f"{t.n} & {t.fp + t.fn} & {t.conv if t.converts else '--'} & {t.alg} & "
                     f"{t.unsplit if t.converts else '--'} & {t.cdiff}\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/peers.tex", "\n".join(lines) + "\n")
    for key, pred in (("peers", lambda t: t.kind == "peer"), ("round24", lambda t: t.converts and t.kind != "peer")):
        chosen = [t for (q, m), t in tally_q.items() if pred(t)]
        N[f"split:{key}:wrong"] = str(sum(t.fp + t.fn for t in chosen))
        N[f"split:{key}:conv"] = str(sum(t.conv for t in chosen))
        N[f"split:{key}:alg"] = str(sum(t.alg for t in chosen))
        N[f"split:{key}:unsplit"] = str(sum(t.unsplit for t in chosen))
    # Ratios of median times quoted in the text: certified against the seeds in double.
    for q in per_query:
        cert = tally_q.get((q, "certified/exact"))
        if not cert:
            continue
        for (qq, m), t in tally_q.items():
            if qq == q and m.endswith("/double") and t.ns and cert.ns:
                N[f"nsratio:{q}:{m}"] = f"{upper_median(cert.ns) / upper_median(t.ns):.1f}"

    # Per family (summary_families.csv): counts for the text.
    for r in families:
        key = f"{r['query']}:{r['family']}:{r['method']}"
        N[f"famwrong:{key}"] = str(int(r["false_positive"]) + int(r["false_negative"]))
        N[f"famfp:{key}"] = str(int(r["false_positive"]))
        N[f"famfn:{key}"] = str(int(r["false_negative"]))
        N[f"famn:{key}"] = str(int(r["n"]))
        N[f"famcls:{key}"] = str(int(r["class_mismatch"]))
    # Class mismatches in exact arithmetic (CORE::Expr): algorithmic, not rounding. Per algorithm
    # and family (the queries pooled), from instances.csv: the queries, the class mismatches and the
    # instances judged in CORE::Expr, the same at 256 bits beside, and which answer was given for
    # which; the corrected seeds listed, the seeds as written counted.
    exact = defaultdict(lambda: {"queries": set(), "core_expr": [0, 0], "gmpfr<256>": [0, 0], "how": Counter(), "kind": ""})
    for r in rows:
        base, nt = cr.split_method(r["method"])
        if nt not in ("core_expr", "gmpfr<256>") or r["outcome"] not in cr.DECIDED:
            continue
        g = exact[(base, r["family"])]
        g["kind"] = r["kind"]
        g[nt][1] += 1
        if r["outcome"] == "class_mismatch":
            g[nt][0] += 1
            g["queries"].add(r["query"])
            if nt == "core_expr":
                g["how"][(r["answer"], r["certified_answer"])] += 1
    exact_cls = sorted(k for k, g in exact.items() if g["core_expr"][0] > 0)
    items = []
    for base, f in exact_cls:
        g = exact[(base, f)]
        if g["kind"] == "seed_as_written":
            continue
        qs = ", ".join(QUERY_TEX.get(q, tex_escape(q)) for q in QUERY_TEX if q in g["queries"])
        how = ", ".join(f"\\textsf{{{a}}} for \\textsf{{{c}}}" for (a, c), _ in g["how"].most_common())
        c, n = g["core_expr"]
        at256 = f", {g['gmpfr<256>'][0]} of {g['gmpfr<256>'][1]} at 256 bits" if g["gmpfr<256>"][1] else ""
        items.append(f"{tex_escape(base)} on {tex_escape(f)} ({qs}): {c} of {n} in \\nt{{CORE::Expr}}{at256}, {how}")
    as_written = sum(exact[k]["kind"] == "seed_as_written" for k in exact_cls)

    def families_text(n):
        return {0: "no family", 1: "1 family"}.get(n, f"{n} families")

    N["clsexact:count"] = str(len(items))
    N["clsexact:families"] = families_text(len(items))
    N["clsexact:list"] = "; ".join(items) or "none"
    N["clsexact:aswritten"] = families_text(as_written)
    # ---- The uniform sample (uniform.csv): typical-case error rates ----
    # Per query and method, the counts of the study's uniform sample (far more instances than the
    # uniform family of instances.csv); the rates with their 95% Wilson intervals. The table shows
    # every method with a wrong answer (Boolean or three-valued) or without a decided answer on
    # some instance, each line after a comment "% uniform: QUERY METHOD", then per query one line
    # for the others after "% uniform_quiet: QUERY METHOD...", by which paper/check_paper.py
    # recounts it from uniform.csv.
    usample = cr.uniform_sample(res)
    uq = defaultdict(list)
    for r in usample:
        uq[r["query"]].append(r)
    certified_n = {q: int(rs[0]["instances"]) - int(rs[0]["uncertified"]) for q, rs in uq.items()}
    n_uni = min(certified_n.values()) if certified_n else 0
    N["uniform:perquery"] = f"{n_uni:,}".replace(",", "\\,")
    N["uniform:zerobound"] = f"{cr.percent_text(cr.error_interval(0, n_uni)[1])}\\,\\%" if n_uni else "--"
    N["uniform:queries"] = str(len(uq))
    N["uniform:methods"] = str(len(usample))
    for q, rs in uq.items():
        r0 = rs[0]
        N[f"uniform:{q}:n"] = str(certified_n[q])
        for a in ("separated", "touching", "overlapping", "uncertified"):
            N[f"uniform:{q}:{a}"] = str(int(r0[a]))
    # The peers' Boolean rates, pooled over their queries' rows, per method; every other number per
    # query and method.
    uwrong = []
    for r in usample:
        e, q, m = cr.uniform_errors(r), r["query"], r["method"]
        boolean = cr.uniform_boolean(r)
        N[f"udecided:{q}:{m}"] = str(e.decided)
        N[f"ufp:{q}:{m}"] = str(e.fp)
        N[f"ufn:{q}:{m}"] = str(e.fn)
        N[f"ucls:{q}:{m}"] = str(e.cls)
        if e.decided:
            N[f"urate:{q}:{m}"] = f"{cr.percent_text(e.rate)}\\,\\%"
            N[f"uci:{q}:{m}"] = wilson_pct(e.wrong, e.decided) + "\\,\\%"
            if not boolean:
                N[f"urate3:{q}:{m}"] = f"{cr.percent_text(e.rate3)}\\,\\%"
                N[f"uci3:{q}:{m}"] = wilson_pct(e.wrong3, e.decided) + "\\,\\%"
        if e.wrong3 or cr.uniform_not_decided(r):
            uwrong.append(r)
    bad = [r for r in uwrong if cr.uniform_errors(r).wrong3]
    N["uniform:methodswrong"] = str(len({r["method"] for r in bad}))
    N["uniform:methodsall"] = str(len({r["method"] for r in usample}))
    N["uniform:rowswrong"] = str(len(bad))
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}llrrrrrll@{}}", "\\toprule",
             "query & method & decided & FP & FN & class & undec. & Boolean error & three-valued\\\\", "\\midrule"]
    shown_q = 0
    for q in QUERY_TEX:
        rs = uq.get(q)
        if not rs:
            continue
        if shown_q:
            lines.append("\\midrule")
        shown_q += 1
        first = True
        noisy = [r for r in rs if r in uwrong]
        noisy.sort(key=lambda r: (-cr.uniform_errors(r).wrong3, r["method"]))
        for r in noisy:
            e = cr.uniform_errors(r)
            lo, hi = e.interval()
            cell = f"{cr.percent_text(e.rate)} ({cr.percent_text(lo)}--{cr.percent_text(hi)})" if e.decided else "--"
            if cr.uniform_boolean(r) or not e.decided:
                cell3 = "--"
            else:
                lo3, hi3 = e.interval(True)
                cell3 = f"{cr.percent_text(e.rate3)} ({cr.percent_text(lo3)}--{cr.percent_text(hi3)})"
            notdecided = cr.uniform_not_decided(r)
            lines.append(f"% uniform: {q} {r['method']}")
            lines.append(f"{QUERY_TEX[q] + f' ({certified_n[q]})' if first else ''} & {method_tex(r['method'])} & {e.decided} & {e.fp} & {e.fn} & "
                         f"{e.cls} & {notdecided} & {cell} & {cell3}\\\\")
            first = False
        quiet = [r for r in rs if r not in uwrong]
        if quiet:
            least = min(cr.uniform_errors(r).decided for r in quiet)
            bound = cr.percent_text(cr.error_interval(0, least)[1]) if least else "--"
            lines.append(f"% uniform_quiet: {q} " + " ".join(r["method"] for r in quiet))
            lines.append(f"{QUERY_TEX[q] + f' ({certified_n[q]})' if first else ''} & \\emph{{{len(quiet)} {'other ' if noisy else ''}methods}} & "
                         f"$\\ge${least} & 0 & 0 & 0 & 0 & 0 ($<${bound}) & \\\\")
    if not shown_q:
        lines.append("\\multicolumn{9}{@{}l}{no uniform sample in this study}\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/uniform_sample.tex", "\n".join(lines) + "\n")
    # Methods without a wrong answer on the sample, per query, for the text.
    for q, rs in uq.items():
        N[f"uniform:{q}:quiet"] = str(sum(1 for r in rs if not cr.uniform_errors(r).wrong3))

    # ---- The seeds in every number type, paired ----
    # The slow number types run on a pseudo-random subset of each family (the study's stride), so
    # an algorithm's number types are compared on the instances where all of them ran: per
    # algorithm and query, the intersection of its types' instances (cr.paired). Each method's
    # tally on those instances is ptally[method]; the text's numbers for these comparisons are
    # the p-keys below, the table's cells the same tallies.
    ran = cr.ran_on(rows)
    seed_bases = {b for b, _ in SEED_BASES}
    paired_ids = {k: v for k, v in cr.paired_by_base(rows, ran, {nt for nt, _ in NTS}).items() if k[1] in seed_bases}
    ptally = defaultdict(Tally)
    for r in rows:
        base, nt = cr.split_method(r["method"])
        if r["instance"] in paired_ids.get((r["query"], base), ()):
            ptally[r["method"]].add(r)
    for base, _ in SEED_BASES:
        N[f"paired:{base}"] = str(sum(len(v) for (q, b), v in paired_ids.items() if b == base))
    for m, t in ptally.items():
        tally_numbers(N, m, t, ("n", "fp", "fn", "cls", "rate", "rate3"), prefix="p")
        N[f"pns:{m}"] = ns_text(percentile(t.ns, 50))
    # Range of the seeds' rates per number type (for the text), Boolean and three-valued, on the
    # paired instances (the table's).
    for nt, _ in NTS:
        ts = [ptally[f"{b}/{nt}"] for b, _ in SEED_BASES if f"{b}/{nt}" in ptally and ptally[f"{b}/{nt}"].decided]
        rates = [t.rate for t in ts]
        rates3 = [t.rate3 for t in ts if t.rate3 is not None]
        if rates:
            N[f"ratemin:{nt}"] = sci(min(rates))
            N[f"ratemax:{nt}"] = sci(max(rates))
        if rates3:
            N[f"rate3min:{nt}"] = sci(min(rates3))
            N[f"rate3max:{nt}"] = sci(max(rates3))

    # ---- Table: seeds by number type (algorithm vs rounding), paired ----
    # Each line of counts follows a comment "% paired: BASE NT...", the number types of its
    # columns, by which paper/check_paper.py recounts it from instances.csv.
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}lr" + "r" * len(NTS) + "@{}}", "\\toprule",
             "algorithm & paired & " + " & ".join(h for _, h in NTS) + "\\\\", "\\midrule"]
    for base, label in SEED_BASES:
        cells, cells2, cells3 = [], [], []
        present = False
        for nt, _ in NTS:
            t = ptally.get(f"{base}/{nt}")
            if t is None or t.n == 0:
                cells.append("")
                cells2.append("")
                cells3.append("")
                continue
            present = True
            cells.append(f"{t.fp}/{t.fn}/{t.cls}")
            extra = f"{t.decided}" + (f", {t.undecided}\\,u" if t.undecided else "")
            cells2.append(f"{{\\scriptsize {extra}}}")
            cells3.append(f"{{\\scriptsize {pct_rate(t.rate)}/{pct_rate(t.rate3)}}}")
        if present:
            lines.append(f"% paired: {base} " + " ".join(nt for nt, _ in NTS))
            lines.append(f"{label} & {N.values[f'paired:{base}']} & " + " & ".join(cells) + "\\\\")
            lines.append(" & & " + " & ".join(cells2) + "\\\\")
            lines.append(" & & " + " & ".join(cells3) + "\\\\[1pt]")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/seeds_by_type.tex", "\n".join(lines) + "\n")

    # ---- Table: the other methods ----
    order = {"certified": 0, "robust": 1, "peer": 2, "sweep": 3}
    others = sorted((m for m, t in tally.items() if t.kind in order), key=lambda m: (order[tally[m].kind], m))
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}lrrrrrrr@{}}", "\\toprule",
             "method & $q$ & $n$ & FP & FN & class & rate & 3-val.\\\\", "\\midrule"]
    last = None
    for m in others:
        t = tally[m]
        if last is not None and t.kind != last:
            lines.append("\\midrule")
        last = t.kind
        # No time: a median pooled over queries whose times differ by orders of magnitude means
        # nothing (the times per query are in tables/timings.tex).
        lines.append(f"{method_tex(m)} & {len(t.queries)} & {t.n} & {t.fp} & {t.fn} & {t.cls} & {sci(t.rate)} & {sci(t.rate3)}\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/other_methods.tex", "\n".join(lines) + "\n")

    # ---- Timing (timing.csv, timing_stages.csv, timing_thread.csv) ----
    # The protocol: one thread, pinned (or not, with the reason), every call repeated until the
    # budget had elapsed; the distributions per query, method and input class; the certified
    # cylinder pairs by deciding stage; and the stages that decided the generic pairs.
    budgets = sorted({fnum(r["budget_ns"]) for r in timing_thread})
    N["timing:budget"] = " and ".join(ns_text(b) for b in budgets) or "--"
    N["timing:measurements"] = " and ".join(sorted({r["measurements"] for r in timing_thread})) or "--"
    pinned = [r for r in timing_thread if r["pinned"] == "1"]
    if timing_thread and len(pinned) == len(timing_thread):
        cpus = sorted({r["cpu"] for r in pinned})
        N["timing:thread"] = ("one thread pinned to CPU " + ", ".join(cpus)) if len(timing_thread) == 1 else \
            f"one thread per shard, each pinned to one CPU ({len(timing_thread)} shards)"
    else:
        N["timing:thread"] = f"one thread, not pinned on {len(timing_thread) - len(pinned)} of {len(timing_thread)} runs " \
            f"({tex_escape('; '.join(sorted({r['note'] for r in timing_thread if r['pinned'] != '1'})))})"
    STATS = ("n", "p10", "p50", "p90", "mean", "max")

    def stat_cells(r):
        return [r["n"]] + [ns_text(fnum(r[f"{k}_ns"])) for k in STATS[1:]]

    tstat = {}
    for r in timing:
        tstat[(r["query"], r["method"], r["inputs"])] = r
        for k, v in zip(STATS, stat_cells(r)):
            N[f"t{k}:{r['inputs']}:{r['query']}:{r['method']}"] = v
    for r in timing_stages:
        for k, v in zip(STATS, stat_cells(r)):
            N[f"tstage{k}:{r['inputs']}:{r['method']}:{r['stage']}"] = v
    # The stages that decided the cylinder pairs per input class (inputs.csv).
    stage_counts = defaultdict(Counter)
    for r in inputs:
        if r["query"] == "cylinder_cylinder" and r["stage"]:
            stage_counts[cr.input_class(r["family"])][r["stage"]] += 1
    for cls in cr.INPUT_CLASSES:
        c = stage_counts[cls]
        N[f"stagecount:{cls}:total"] = str(sum(c.values()))
        for st in set(c) | {"midpoints", "fast_path", "optimiser", "refine", "touching_exact", "gmpfr", "ellipsoid", "none"}:
            N[f"stagecount:{cls}:{st}"] = str(c.get(st, 0))
        N[f"stagecount:{cls}:others"] = str(sum(c.values()) - c.get("fast_path", 0))

    # Table: the certified query's times per query and input class, then the certified cylinder
    # pairs per deciding stage. Each line of times follows a comment "% timing: QUERY METHOD
    # INPUTS" or "% timing_stage: METHOD STAGE INPUTS", by which paper/check_paper.py recounts
    # it from instances.csv and inputs.csv.
    INPUTS_TEX = {"generic": "generic", "near_degenerate": "near-degen.", "all": "all"}
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}llrrrrrr@{}}", "\\toprule",
             "query & inputs & $n$ & p10 & p50 & p90 & mean & max\\\\", "\\midrule"]
    for q in QUERY_TEX:
        for cls in cr.INPUT_CLASSES:
            r = tstat.get((q, "certified/exact", cls))
            if r is None:
                continue
            lines.append(f"% timing: {q} certified/exact {cls}")
            lines.append(f"{QUERY_TEX[q]} & {INPUTS_TEX[cls]} & " + " & ".join(stat_cells(r)) + "\\\\")
    STAGE_ORDER = ["midpoints", "fast_path", "optimiser", "refine", "touching_exact", "gmpfr", "ellipsoid", "none"]
    staged = sorted((r for r in timing_stages if r["method"] == "certified/exact" and r["inputs"] == "all"),
                    key=lambda r: STAGE_ORDER.index(r["stage"]) if r["stage"] in STAGE_ORDER else 99)
    if staged:
        lines.append("\\midrule")
        lines.append("\\multicolumn{8}{@{}l}{\\emph{cylinder pair, by the stage that decided}}\\\\")
        for r in staged:
            lines.append(f"% timing_stage: certified/exact {r['stage']} all")
            lines.append(f"{tex_escape(r['stage'])} & all & " + " & ".join(stat_cells(r)) + "\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/timing_certified.tex", "\n".join(lines) + "\n")

    # Table: median time per query, the certified query against the methods in double (Bullet:
    # float), near-degenerate and generic inputs apart, each query on the instances where every
    # method shown for it ran (all of them: these methods run on every instance).
    qs = [q for q in QUERY_TEX if q in per_query]
    ms = sorted({m for (q, m), t in tally_q.items() if t.kind != "sweep" and (m.endswith("/double") or m.endswith("/float") or m == "certified/exact")},
                key=lambda m: (m != "certified/exact", m))
    common = {q: cr.paired(rows, q, [m for m in ms if (q, m) in ran], ran) for q in qs}
    ns_in = defaultdict(lambda: defaultdict(list))  # (query, method) -> input class -> times
    for r in rows:
        if r["instance"] in common.get(r["query"], ()) and r["method"] in ms and r["answer"] != "process_ended":
            ns_in[(r["query"], r["method"])][cr.input_class(r["family"])].append(fnum(r["ns"]))
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}l" + "r" * len(qs) + "@{}}", "\\toprule",
             "method & " + " & ".join(QUERY_TEX[q] for q in qs) + "\\\\",
             "$n$ (near-degen./generic) & " + " & ".join(
                 f"{sum(1 for r in inputs if r['query'] == q and r['instance'] in common[q] and r['family'] != 'uniform')}/"
                 f"{sum(1 for r in inputs if r['query'] == q and r['instance'] in common[q] and r['family'] == 'uniform')}" for q in qs) + "\\\\",
             "\\midrule"]
    for q in qs:
        N[f"timingpaired:{q}"] = str(len(common[q]))
    for m in ms:
        cells, cells2 = [], []
        for q in qs:
            v = ns_in.get((q, m), {})
            near, gen = v.get("near_degenerate", []), v.get("generic", [])
            cells.append(ns_text(percentile(near, 50)) if near else "")
            cells2.append(f"{{\\scriptsize {ns_text(percentile(gen, 50))}}}" if gen else "")
        lines.append(f"{method_tex(m)} & " + " & ".join(cells) + "\\\\")
        lines.append(" & " + " & ".join(cells2) + "\\\\[1pt]")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/timings.tex", "\n".join(lines) + "\n")

    # ---- t error (line queries), aggregated over the four line queries ----
    # Per query and method for the text; the table pools the line queries per method, in the
    # number types that show the spread (Gullotti as written has Gullotti's formulas for t).
    for (q, m), v in terr.items():
        N[f"terr50:{q}:{m}"] = sci(percentile(v, 50))
        N[f"terr99:{q}:{m}"] = sci(percentile(v, 99))
        N[f"terrmax:{q}:{m}"] = sci(percentile(v, 100))
    shown_nts = ["exact", "double", "long_double", "interval", "gmpfr<53>", "gmpfr<113>", "core_expr"]
    def t_order(m):
        base, _, nt = m.partition("/")
        return (["certified", "robust", "shene", "gullotti"].index(base) if base in ("certified", "robust", "shene", "gullotti") else 9,
                shown_nts.index(nt) if nt in shown_nts else 99)
    # The table compares the number types on the same instances: per query, those on which every
    # method it shows ran (the slow types run on a subset), pooled over the line queries.
    t_shown = {m for (q, m) in terr if t_order(m)[0] < 9 and t_order(m)[1] < 99}
    t_common = {q: cr.paired(rows, q, sorted(m for (qq, m) in ran if qq == q and m in t_shown), ran)
                for q in {q for q, _ in terr}}
    pooled = defaultdict(list)
    for r in rows:
        t = fnum(r["t_error_ulps"])
        if r["method"] in t_shown and not math.isnan(t) and r["instance"] in t_common[r["query"]]:
            pooled[r["method"]].append(t)
    N["terr:paired"] = str(sum(len(v) for v in t_common.values()))
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}lrrrrr@{}}", "\\toprule",
             "method & $n$ & median & p90 & p99 & max\\\\", "\\midrule"]
    for m in sorted((m for m in pooled if t_order(m)[0] < 9 and t_order(m)[1] < 99), key=t_order):
        v = pooled[m]
        p50, p90, p99, mx = (percentile(v, p) for p in (50, 90, 99, 100))
        N[f"terr50:{m}"] = sci(p50)
        N[f"terr99:{m}"] = sci(p99)
        N[f"terrmax:{m}"] = sci(mx)
        lines.append(f"{method_tex(m)} & {len(v)} & {sci(p50)} & {sci(p90)} & {sci(p99)} & {sci(mx)}\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/t_error.tex", "\n".join(lines) + "\n")

    # ---- errors against k (instances.csv): the rate per bin of k with Wilson intervals ----
    # For the methods of K_TABLE_METHODS, per query: one pair of lines per error measure, the
    # wrong answers over the decided ones per bin of cr.K_BINS and over all k, then the 95% Wilson
    # interval in percent; the three-valued measure only for a three-valued method with a class
    # mismatch (otherwise it equals the Boolean one, or is undefined). Each measure's first line
    # is preceded by a comment "% error_by_k: QUERY METHOD MEASURE", which paper/check_paper.py
    # reads to recount the line's cells from instances.csv.
    by_k = cr.errors_by_k(rows)
    boolean = cr.boolean_methods(rows)
    nb = len(cr.K_BINS)

    def k_head(b):
        lo, hi = cr.K_BINS[b]
        return "$0$" if lo is None else (f"$\\ge2^{{{lo}}}$" if hi is None else f"$2^{{{lo}}}$")

    def k_words(b):
        lo, hi = cr.K_BINS[b]
        return "$k=0$" if lo is None else (f"$|k|\\ge2^{{{lo}}}$" if hi is None else f"$2^{{{lo}}}\\le|k|<2^{{{hi}}}$")

    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}ll" + "r" * (nb + 1) + "@{}}", "\\toprule",
             "method & error & " + " & ".join(k_head(b) for b in range(nb)) + " & all $k$\\\\", "\\midrule"]
    shown = 0
    for q, ms in K_TABLE_METHODS:
        present = [m for m in ms if (q, m) in by_k]
        if not present:
            continue
        if shown:
            lines.append("\\midrule")
        lines.append(f"\\multicolumn{{{nb + 3}}}{{@{{}}l}}{{\\emph{{{QUERY_TEX.get(q, tex_escape(q))}}}}}\\\\")
        for m in present:
            bins = by_k[(q, m)]
            total = cr.Errors.pooled(bins)
            # The numbers the text quotes, for the Boolean error and, for a three-valued method
            # (with or without class mismatches), the three-valued one; per bin, over all k and
            # over k != 0; the highest bin with a wrong answer.
            nonzero = cr.Errors.pooled(bins[1:])
            for key, three in (("boolean", False), ("three_valued", True)):
                if three and m in boolean:
                    continue
                for tag, e in [(str(b), e) for b, e in enumerate(bins)] + [("all", total), ("nonzero", nonzero)]:
                    w = e.wrong3 if three else e.wrong
                    N[f"kwrong:{key}:{q}:{m}:{tag}"] = str(w)
                    N[f"kn:{key}:{q}:{m}:{tag}"] = str(e.decided)
                    if e.decided:
                        N[f"krate:{key}:{q}:{m}:{tag}"] = f"{cr.percent_text(w / e.decided)}\\,\\%"
                        N[f"kci:{key}:{q}:{m}:{tag}"] = f"{wilson_pct(w, e.decided)}\\,\\%"
                last = max((b for b, e in enumerate(bins) if (e.wrong3 if three else e.wrong)), default=None)
                N[f"klast:{key}:{q}:{m}"] = "none" if last is None else k_words(last)
            # The table: the three-valued lines only where class mismatches make them differ.
            measures = [("boolean", "FP+FN", False)]
            if m not in boolean and total.cls:
                measures.append(("three_valued", "+class", True))
            for key, label, three in measures:
                counts = [(e.wrong3 if three else e.wrong, e.decided) for e in bins + [total]]
                lines.append(f"% error_by_k: {q} {m} {key}")
                # The method's algorithm on its first line of counts, its number type on the line
                # of intervals below (one cell of the method's name is the widest of the table).
                base, nt = cr.split_method(m)
                first, second = ("", "") if three else (tex_escape(base), f"\\texttt{{{tex_escape(nt)}}}")
                lines.append(f"{first} & {label} & " + " & ".join(f"{w}/{n}" if n else "" for w, n in counts) + "\\\\")
                lines.append(f"{second} & & " + " & ".join(f"{{\\tiny {wilson_pct(w, n)}}}" if n else "" for w, n in counts)
                             + "\\\\[1pt]")
            shown += 1
    if not shown:
        lines.append(f"\\multicolumn{{{nb + 3}}}{{@{{}}l}}{{none of the methods shown was run}}\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/error_by_k.tex", "\n".join(lines) + "\n")
    for b in range(nb):
        N[f"kbin:{b}"] = k_words(b)
    N["kbins"] = str(nb)
    N["kbinades"] = str(cr.K_BIN_BINADES)

    # ---- failure maps ----
    mapdir = os.path.join(res, "failure_maps")
    map_rows = []
    if os.path.isdir(mapdir):
        for name in sorted(os.listdir(mapdir)):
            if not name.endswith(".csv"):
                continue
            mrows = read_csv(os.path.join(mapdir, name))
            key = name[:-4]
            jpath = os.path.join(mapdir, key + ".json")
            if os.path.exists(jpath):
                note_read(jpath)
            methods = [c for c in mrows[0] if c not in ("i", "j", "d0_ulps", "d1_ulps", "certified", "gap_lo", "gap_hi")]
            N[f"map:{key}:cells"] = str(len(mrows))
            cert = Counter(r["certified"] for r in mrows)
            for a, code in (("separated", "s"), ("touching", "t"), ("overlapping", "o")):
                N[f"map:{key}:cert:{a}"] = str(cert.get(code, 0))
            for m in methods:
                # A cell "." (a slow method off its sub-grid) was not evaluated.
                wrong = undec = cls = 0
                for r in mrows:
                    c = r[m]
                    # c: as the method's contract says where it differs from the solid answer
                    # (not wrong); x: not as it says there (wrong).
                    if c in "uec.":
                        undec += c == "u"
                        continue
                    if c == "x" or (c in "toi") != (r["certified"] in "toi"):
                        wrong += 1
                    elif c + r["certified"] in ("to", "ot"):
                        cls += 1
                N[f"map:{key}:{m}"] = str(wrong)
                N[f"mapcls:{key}:{m}"] = str(cls)
                N[f"map3:{key}:{m}"] = str(wrong + cls)
                N[f"mapundec:{key}:{m}"] = str(undec)
                map_rows.append((key, m, wrong, undec, cls))
    maps = sorted({k for k, *_ in map_rows})
    mlist = sorted({m for _, m, *_ in map_rows}, key=lambda m: (m.split("/")[0], m))
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}l" + "r" * len(maps) + "@{}}", "\\toprule",
             "method & " + " & ".join(tex_escape(k.replace("_", " ")) for k in maps) + "\\\\", "\\midrule"]
    cell = {(k, m): (w, u, c) for k, m, w, u, c in map_rows}
    for m in mlist:
        cs = []
        for k in maps:
            if (k, m) in cell:
                w, u, c = cell[(k, m)]
                cs.append(f"{w}" + (f"\\,+\\,{c}\\,c" if c else "") + (f" ({u}\\,u)" if u else ""))
            else:
                cs.append("")
        lines.append(f"{method_tex(m)} & " + " & ".join(cs) + "\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/maps.tex", "\n".join(lines) + "\n")

    # ---- hunting ----
    def gap_size_tex(query):
        """The certified lower bound of the signed gap's size, named by its quantity."""
        return "$|\\log\\varphi^*| \\ge$" if query == "cylinder_cylinder" else "$|G| \\ge$"

    found = []
    for r in hunt:
        if r["found"] != "1" or r["outcome"] not in ("false_positive", "false_negative"):
            continue
        found.append((gap_bound(r), r))
    # The signed gap is the depth margin G for the queries against one cylinder and log(phi*) for
    # cylinder pairs (src/study/gap.hpp): different quantities, so rows of the two are not ranked
    # against each other (depth margins first).
    found.sort(key=lambda x: (x[1]["query"] == "cylinder_cylinder", -x[0], x[1]["method"]))
    # Searches (one per method and query: hunt.csv's rows) and methods are different units: the
    # searches that found a wrong answer of the searches, the methods with one of the methods.
    N["hunt:searches"] = str(len(hunt))
    N["hunt:found"] = str(len(found))
    N["hunt:methodcount"] = str(len({r["method"] for r in hunt}))
    evaluations = [int(r["evaluations"]) for r in hunt if r["evaluations"]]
    N["hunt:evaluations"] = str(max(evaluations, default=0))
    N["hunt:evalsmin"] = str(min(evaluations, default=0))
    N["hunt:evalspair"] = str(max((int(r["evaluations"]) for r in hunt if r["evaluations"] and r["query"] == "cylinder_cylinder"
                                   and not r["method"].endswith("/core_expr")), default=0))
    for g, r in found:
        # Per query and method; the key without the query names the method's worst case
        # (found is sorted by decreasing gap, so the first row of a method is its worst).
        for m in (f"{r['query']}:{r['method']}", r["method"]):
            if f"huntgap:{m}" in N.values:
                continue
            N[f"huntgap:{m}"] = sci_down(g)
            N[f"huntfamily:{m}"] = tex_escape(r["start_family"])
            N[f"huntanswer:{m}"] = tex_escape(r["answer"])
            N[f"huntcert:{m}"] = tex_escape(r["certified_answer"])
    per_method = []
    seen = set()
    for g, r in found:
        if r["method"] not in seen:
            seen.add(r["method"])
            per_method.append((g, r))
    N["hunt:methodswrong"] = str(len(per_method))
    lines = ["% Generated by paper/make_tables.py: do not edit.",
             "\\begin{tabular}{@{}lllllr@{}}", "\\toprule",
             "method & query & family & answer & certified & signed gap\\\\", "\\midrule"]
    # The HUNT_ROWS largest, then every peer library's worst case below them (the peers are
    # discussed in the text whatever their rank).
    shown = per_method[:HUNT_ROWS] + [(g, r) for g, r in per_method[HUNT_ROWS:]
                                      if tally.get(r["method"]) is not None and tally[r["method"]].kind == "peer"]
    for g, r in shown:
        lines.append(f"{method_tex(r['method'])} & {QUERY_TEX.get(r['query'], tex_escape(r['query']))} & {tex_escape(r['start_family'])} & "
                     f"{tex_escape(r['answer'])} & {tex_escape(r['certified_answer'])} & {gap_size_tex(r['query'])} {sci_down(g)}\\\\")
    lines += ["\\bottomrule", "\\end{tabular}"]
    write(out, "tables/hunt.tex", "\n".join(lines) + "\n")
    N["hunt:shown"] = str(len(shown))
    N["hunt:peerswrong"] = str(sum(1 for g, r in per_method if tally.get(r["method"]) is not None and tally[r["method"]].kind == "peer"))

    # The inputs of the worst case per query among the methods in hardware precision (double,
    # long double, float: as users run them), in hexfloats (reproducible with certcyl).
    worst = {}
    for g, r in found:
        if r["method"].partition("/")[2] in ("double", "long_double", "float"):
            worst.setdefault(r["query"], (g, r))
    lines = ["% Generated by paper/make_tables.py: do not edit."]
    for q in [q for q in QUERY_TEX if q in worst]:
        g, r = worst[q]
        xs = r["input_hex"].split()
        body = ", ".join(hexfloat_tex(x) for x in xs)
        lines.append(f"\\item[{QUERY_TEX[q]}] {method_tex(r['method'])} answers {tex_escape(r['answer'])}, certified "
                     f"{tex_escape(r['certified_answer'])}, {gap_size_tex(q)} {sci_down(g)}. Input ({len(xs)} coordinates): "
                     f"{{\\footnotesize\\raggedright {body}\\par}}")
    if len(lines) == 1:
        lines.append("\\item[--] no wrong answer was found by the search.")
    write(out, "tables/hunt_inputs.tex", "\n".join(lines) + "\n")

    # CORE::Expr's warnings (Core_Diagnostics, written only when there are any: one line each,
    # "CORE WARNING (at FILE: LINE): MESSAGE").
    core = Counter()
    cpath = os.path.join(res, "Core_Diagnostics")
    if os.path.exists(cpath):
        note_read(cpath)
        with open(cpath, errors="replace") as f:
            for line in f:
                if line.strip():
                    core[line.rsplit("): ", 1)[-1].strip()] += 1
    N["core:warnings"] = str(sum(core.values()))
    N["core:zerodivisor"] = str(core.get("possible zero divisor!", 0))
    N["core:negsqrt"] = str(core.get("possible negative sqrt!", 0))
    N["core:other"] = str(sum(core.values()) - core.get("possible zero divisor!", 0) - core.get("possible negative sqrt!", 0))

    write(out, "numbers.tex", N.text())
    units = {k: count_unit(k) for k in sorted(N.values)}  # null: not a count
    write(out, "units.json", json.dumps(units, indent=1, sort_keys=True) + "\n")

    write_manifest("paper/make_tables.py", res, out, WRITTEN)
    print(f"make_tables: {len(N.values)} numbers and {len(WRITTEN) - 2} tables written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
