"""Reading a results folder of `certcyl study` or `certcyl judge`: what the scripts of experiments/
and paper/ share.

    sys.path.insert(0, "<source>/experiments"); import certcyl_results as cr

  read_csv(path)          rows of a CSV file as dicts; every path read is kept in READ (for the
                          manifests that tie figures and tables to the files they come from)
  note_read(path)         keeps a path read otherwise (a JSON file) in READ
  sha256(path)            hex SHA-256 of a file
  write_manifest(generator, results, out, written)
                          OUT/manifest.json: the SHA-256 of every file in READ and in `written`
  read_judged_speed(path) the rows of a judge's speed.csv (its method's point on the study's
                          speed-against-error figure), checked; ValueError naming the file when
                          it is missing or malformed
  fnum(s)                 a CSV field as a float, NaN when empty
  wilson(k, n)            the 95% Wilson score interval of k successes in n trials
  error_interval(k, n)    the same with its ends exact: 0 when k is 0, 1 when k is n
  percent_text(p)         a proportion in percent, two significant digits ("0", "0.41", "37", "100")
  upper_median, percentile
  OUTCOMES, FAILURES      the study's outcome names; those counted as failures (FP + FN)
  DECIDED                 the outcomes of a decided answer (agree, FP, FN, class mismatch)
  Errors                  decided answers and wrong ones (FP, FN, class mismatches) of a set of
                          instance rows: the Boolean error rate (FP + FN) / decided and the
                          three-valued one (FP + FN + class) / decided, each with its Wilson interval
  boolean_methods(rows)   the methods that answered `intersecting` (no three-valued answer)
  uniform_errors(r)       the Errors of a row of uniform.csv (the uniform sample's counts of a
                          query and method); uniform_boolean(r): whether it is a Boolean method;
                          uniform_not_decided(r): its undecided, error and invalid answers
  uniform_sample(folder)  the rows of FOLDER/uniform.csv, [] when the study wrote none
  K_BINS, k_bin(k)        the bins of k_ulps (k = 0, then four binades a bin) and a value's bin
  errors_by_k(rows)       (query, method) -> one Errors per bin of K_BINS, hard-case families only
  ran_on(rows)            (query, method) -> the instances (ids) the method ran on
  paired(rows, query, methods)  the instances of `query` on which every method of `methods` ran:
                          the common ground of a comparison (the slow number types run on a
                          pseudo-random subset of each family only)
  paired_speed_error(rows, query, methods)
                          (the paired instances, method -> (median ns, Boolean rate, decided)) on
                          the instances of `query` where every method ran: a speed-against-error
                          point per method that compares like with like
  Tally                   a method's rows on a set of instances: n, the outcomes not decided,
                          the Errors of the decided answers, the times
  paired_by_base(rows, ran, numbers)
                          (query, algorithm) -> the instances where every number type of the
                          algorithm (those of `numbers`, when given) ran
  paired_by_algorithm(rows)
                          per query, each algorithm's number types compared on the instances
                          where all of them ran: (query, method) -> PairedTally (a Tally with the
                          paired count)
  input_class(family)     "generic" (the uniform family) or "near_degenerate" (a hard-case family)
  time_stats(values)      (n, p10, p50, p90, mean, max) of times: nearest-rank percentiles and the
                          mean summed in the given order, as the study's timing*.csv files
  ns_tex(ns)              a time for LaTeX: "81\\,ns", "2.44\\,\\ensuremath{\\mu}s", "24.1\\,ms", "--"
  split_method(m)         "shene_as_written/double" -> ("shene_as_written", "double")
  method_label(m)         the same for a reader: "shene (as written), double"
  QUERY_TITLES            query name -> short title
  html_table(header, rows)  an HTML table, cells escaped (the index page of a results folder)
Pure standard library (no numpy, no matplotlib), so that any script may import it.
"""
import csv
import hashlib
import json
import math
import os
from html import escape

READ = []  # every file read through read_csv or note_read, in order

OUTCOMES = ("agree", "false_positive", "false_negative", "class_mismatch", "undecided", "error", "invalid", "uncertified")
FAILURES = ("false_positive", "false_negative")
# A decided answer: the method gave one (not undecided, error or invalid) on a certified instance.
DECIDED = ("agree", "false_positive", "false_negative", "class_mismatch")

QUERY_TITLES = {
    "line_cylinder": "line",
    "ray_cylinder": "ray",
    "segment_cylinder": "segment",
    "line_elliptic_cylinder": "line, elliptic cylinder",
    "triangle_cylinder": "triangle",
    "cylinder_cylinder": "cylinder pair",
}


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def write_manifest(generator, results, out, written):
    """Writes out/manifest.json: the generator's name, the SHA-256 of every file in READ (keyed
    by its path relative to `results`) and of every path in `written` (relative to `out`)."""
    manifest = {
        "generator": generator,
        "inputs": {os.path.relpath(p, results): sha256(p) for p in sorted(set(READ))},
        "outputs": {os.path.relpath(p, out): sha256(p) for p in sorted(set(written))},
    }
    with open(os.path.join(out, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1, sort_keys=True)
        f.write("\n")


def note_read(path):
    READ.append(path)


def read_csv(path):
    READ.append(path)
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# The columns of a judge's speed.csv that a reader needs (src/judge_report.cpp writes them with the
# columns of the study's summary.csv, mean_ns in place of median_ns).
JUDGED_SPEED_COLUMNS = ("query", "method", "kind", "disagreement_rate", "mean_ns")


def read_judged_speed(path):
    """The rows of `path`, the speed.csv of `certcyl judge`, as dicts of strings (fields quoted as
    RFC 4180), kept in READ. ValueError, its message naming `path`, when the file cannot be read,
    lacks a column of JUDGED_SPEED_COLUMNS, has no row, a row of another length than the header,
    a kind other than "judged", an empty query or method, a disagreement rate that is not a
    number in [0, 1] or a mean_ns that is not a finite number > 0."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            table = list(csv.reader(f, strict=True))
    except (OSError, UnicodeError, csv.Error) as e:
        raise ValueError(f"{path}: cannot be read as CSV ({e})") from None
    if not table:
        raise ValueError(f"{path}: empty (no header line)")
    header = table[0]
    missing = [c for c in JUDGED_SPEED_COLUMNS if c not in header]
    if missing:
        raise ValueError(f"{path}: not a judge's speed.csv, no column {', '.join(missing)} (header: {','.join(header)})")
    if len(table) == 1:
        raise ValueError(f"{path}: no row after the header")
    note_read(path)
    rows = []
    for line, fields in enumerate(table[1:], start=2):
        if len(fields) != len(header):
            raise ValueError(f"{path}: row {line} has {len(fields)} fields, the header {len(header)}")
        r = dict(zip(header, fields))
        if r["kind"] != "judged":
            raise ValueError(f"{path}: row {line}: kind '{r['kind']}', not 'judged'")
        if not r["query"] or not r["method"]:
            raise ValueError(f"{path}: row {line}: empty query or method")
        try:
            rate, ns = float(r["disagreement_rate"]), float(r["mean_ns"])
        except ValueError:
            raise ValueError(f"{path}: row {line}: disagreement_rate '{r['disagreement_rate']}' or mean_ns '{r['mean_ns']}' "
                             "is not a number") from None
        if not 0.0 <= rate <= 1.0:
            raise ValueError(f"{path}: row {line}: disagreement_rate {r['disagreement_rate']} is not in [0, 1]")
        if not (math.isfinite(ns) and ns > 0.0):
            raise ValueError(f"{path}: row {line}: mean_ns {r['mean_ns']} is not a finite number > 0")
        rows.append(r)
    return rows


def fnum(s):
    if s in ("", None):
        return math.nan
    return float(s)


def wilson(k, n, z=1.959963984540054):
    """The Wilson score interval (lo, hi) of the proportion k/n at the confidence of z (95% by
    default); (0, 1) when n is 0."""
    if n <= 0:
        return 0.0, 1.0
    p = k / n
    denom = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z / denom * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


class Errors:
    """The decided answers of a set of instance rows (outcome in DECIDED) and the wrong ones among
    them: false positives, false negatives and class mismatches. Two error rates over the same
    decided answers:
      Boolean        (FP + FN) / decided: says the sets meet or not, wrongly (the study's
                     disagreement_rate; summary.csv)
      three-valued   (FP + FN + class) / decided: the answer is not the certified one of separated,
                     touching and overlapping; defined for a three-valued method only (a Boolean
                     method, which answers `intersecting`, gives no touching or overlapping, so
                     its three-valued error is undefined and shown as a dash, not as 0)
    A rate with nothing decided is NaN."""

    __slots__ = ("decided", "fp", "fn", "cls")

    def __init__(self):
        self.decided = self.fp = self.fn = self.cls = 0

    def add(self, outcome):
        if outcome not in DECIDED:
            return
        self.decided += 1
        self.fp += outcome == "false_positive"
        self.fn += outcome == "false_negative"
        self.cls += outcome == "class_mismatch"

    @property
    def wrong(self):
        return self.fp + self.fn

    @property
    def wrong3(self):
        return self.fp + self.fn + self.cls

    @property
    def rate(self):
        return self.wrong / self.decided if self.decided else math.nan

    @property
    def rate3(self):
        return self.wrong3 / self.decided if self.decided else math.nan

    @classmethod
    def pooled(cls, parts):
        """The Errors of the union of `parts` (Errors of disjoint sets of rows)."""
        total = cls()
        for e in parts:
            total.decided += e.decided
            total.fp += e.fp
            total.fn += e.fn
            total.cls += e.cls
        return total

    def interval(self, three_valued=False):
        """The 95% Wilson interval of the Boolean (or the three-valued) error rate."""
        return error_interval(self.wrong3 if three_valued else self.wrong, self.decided)


def uniform_errors(r):
    """The Errors of a row of uniform.csv: its decided answers and wrong ones, counted by the study
    (the uniform sample keeps counts, not one row per instance)."""
    e = Errors()
    e.decided, e.fp, e.fn, e.cls = (int(r[k]) for k in ("decided", "false_positive", "false_negative", "class_mismatch"))
    return e


def uniform_not_decided(r):
    """The instances of a row of uniform.csv that its method did not decide: undecided, error or
    invalid."""
    return int(r["undecided"]) + int(r["error"]) + int(r["invalid"])


def uniform_boolean(r):
    """Whether the method of a row of uniform.csv answered `intersecting` (a Boolean method: no
    three-valued error)."""
    return int(r["intersecting"]) > 0


def uniform_sample(folder):
    """The rows of folder/uniform.csv (read through read_csv), [] when the folder has none."""
    path = os.path.join(folder, "uniform.csv")
    return read_csv(path) if os.path.exists(path) else []


def boolean_methods(rows):
    """The methods of `rows` (instances.csv) that answered `intersecting` at least once: Boolean
    methods, whose three-valued error is not defined."""
    return {r["method"] for r in rows if r["answer"] == "intersecting"}


# The bins of k, the ulps a hard-case instance was moved off its family's degeneracy. The study
# draws k = 0 for one instance in eight and otherwise +-(2^e + j), e uniform in {0, ..., 40},
# 0 <= j <= 2^(e-1), so |k| < 2^41: the bins are k = 0, then |k| in [2^(4i), 2^(4i+4)) for
# i = 0, ..., 8, and |k| >= 2^36 (binades 36 to 40). Each bin is (lowest exponent, exponent above
# or None when open): (None, None) for k = 0.
K_BIN_BINADES = 4
K_BINS = ((None, None),) + tuple((4 * i, 4 * i + 4) for i in range(9)) + ((36, None),)


def k_bin(k):
    """The index into K_BINS of k (a k_ulps field or a number); None when empty."""
    if k in ("", None):
        return None
    k = abs(float(k))
    if k == 0:
        return 0
    e = max(0, math.floor(math.log2(k)))
    return 1 + min(len(K_BINS) - 2, e // K_BIN_BINADES)


def k_bin_label(b, power="2^{}"):
    """A bin of K_BINS in words: "0", "[2^0, 2^4)", ">= 2^36", the powers written by `power`."""
    lo, hi = K_BINS[b]
    if lo is None:
        return "0"
    if hi is None:
        return ">= " + power.format(lo)
    return f"[{power.format(lo)}, {power.format(hi)})"


def errors_by_k(rows):
    """(query, method) -> a list of one Errors per bin of K_BINS, from the rows of instances.csv
    of the hard-case families (the uniform family has no degeneracy to be k ulps from, and
    uncertified instances are judged by no method)."""
    out = {}
    for r in rows:
        if r["family"] == "uniform" or r["outcome"] not in DECIDED:
            continue
        b = k_bin(r["k_ulps"])
        if b is None:
            continue
        bins = out.get((r["query"], r["method"]))
        if bins is None:
            bins = out[(r["query"], r["method"])] = [Errors() for _ in K_BINS]
        bins[b].add(r["outcome"])
    return out


def error_interval(k, n):
    """wilson(k, n) with the bound at an end exact: the lower bound 0 when k is 0 and the upper
    bound 1 when k is n (the formula leaves a rounding error of about 1e-15 there)."""
    lo, hi = wilson(k, n)
    return (0.0 if k == 0 else lo), (1.0 if k == n else hi)


def percent_text(p):
    """A proportion p in [0, 1] in percent with two significant digits, without an exponent: "0",
    "0.0041", "3.5", "37", "100" (99.5 % and above)."""
    x = 100.0 * p
    if x == 0:
        return "0"
    if x >= 99.5:
        return "100"
    x = float(f"{x:.2g}")  # rounded first, so that 9.996 reads 10, not 10.0
    return f"{x:.{max(0, 1 - math.floor(math.log10(x)))}f}"


def upper_median(values):
    v = sorted(values)
    return v[len(v) // 2] if v else math.nan


def percentile(values, p):
    """Nearest-rank percentile."""
    v = sorted(values)
    if not v:
        return math.nan
    k = max(0, min(len(v) - 1, math.ceil(p / 100.0 * len(v)) - 1))
    return v[k]


def ran_on(rows):
    """(query, method) -> the set of instance ids (strings) of the rows of instances.csv."""
    out = {}
    for r in rows:
        out.setdefault((r["query"], r["method"]), set()).add(r["instance"])
    return out


def paired(rows, query, methods, ran=None):
    """The instance ids of `query` on which every method of `methods` ran (an empty set when one
    of them never ran); `ran` is ran_on(rows), computed when not given."""
    ran = ran_on(rows) if ran is None else ran
    sets = [ran.get((query, m), set()) for m in methods]
    return set.intersection(*sets) if sets else set()


def paired_speed_error(rows, query, methods, ran=None):
    """On the instances of `query` where every method of `methods` ran: the set of those
    instances and, per method, (median ns by nearest rank, Boolean error rate (NaN when nothing
    was decided), decided answers), from the rows of instances.csv (a call that ended its process
    has no time)."""
    common = paired(rows, query, methods, ran)
    wanted = set(methods)
    ns, errs = {m: [] for m in methods}, {m: Errors() for m in methods}
    for r in rows:
        if r["query"] == query and r["method"] in wanted and r["instance"] in common:
            if r["answer"] != "process_ended":
                ns[r["method"]].append(fnum(r["ns"]))
            errs[r["method"]].add(r["outcome"])
    return common, {m: (percentile(ns[m], 50), errs[m].rate, errs[m].decided) for m in methods}


class Tally:
    """A method's rows of instances.csv on some set of instances: `n` (its rows, uncertified ones
    left out), the outcomes not decided (undecided, error, invalid), the Errors of its decided
    answers, and the times (a call that ended its process has none). The counting the summary
    table, the paper's tables and their quoted numbers share."""

    __slots__ = ("n", "undecided", "error", "invalid", "errors", "ns")

    def __init__(self):
        self.n, self.undecided, self.error, self.invalid = 0, 0, 0, 0
        self.errors, self.ns = Errors(), []

    def add(self, r):
        if r["outcome"] == "uncertified":
            return
        self.n += 1
        self.undecided += r["outcome"] == "undecided"
        self.error += r["outcome"] == "error"
        self.invalid += r["outcome"] == "invalid"
        self.errors.add(r["outcome"])
        if r["answer"] != "process_ended":
            self.ns.append(fnum(r["ns"]))

    @property
    def median_ns(self):
        return percentile(self.ns, 50)


class PairedTally(Tally):
    """A Tally on the paired instances of its algorithm and query, with `paired`: how many
    instances every number type of the algorithm ran on."""

    __slots__ = ("paired",)

    def __init__(self, paired):
        super().__init__()
        self.paired = paired


def paired_by_base(rows, ran=None, numbers=None):
    """(query, algorithm) -> the instances of the query on which every number type of the
    algorithm (split_method's base) ran, from the rows of instances.csv; `numbers` (optional)
    restricts the number types compared to those it lists."""
    ran = ran_on(rows) if ran is None else ran
    by_base = {}
    for q, m in ran:
        base, nt = split_method(m)
        if numbers is None or nt in numbers:
            by_base.setdefault((q, base), []).append(m)
    return {k: paired(rows, k[0], ms, ran) for k, ms in by_base.items()}


def paired_by_algorithm(rows):
    """(query, method) -> PairedTally: each method's rows of instances.csv on the instances of its
    query where every number type of its algorithm (split_method's base) ran, so that the number
    types of an algorithm are compared on the same inputs (the slow types run on a pseudo-random
    share of each family only). An algorithm with one number type keeps all of its instances."""
    ran = ran_on(rows)
    common = paired_by_base(rows, ran)
    out = {(q, m): PairedTally(len(common[(q, split_method(m)[0])])) for q, m in ran}
    for r in rows:
        q, m = r["query"], r["method"]
        if r["instance"] in common[(q, split_method(m)[0])]:
            out[(q, m)].add(r)
    return out


# The inputs a time belongs to (the study's timing.csv): the uniform random family is generic
# input; every hard-case family is built on a degeneracy and moved at most 2^41 ulps off it.
INPUT_CLASSES = ("generic", "near_degenerate")


def input_class(family):
    return "generic" if family == "uniform" else "near_degenerate"


def time_stats(values):
    """(n, p10, p50, p90, mean, max) of a list of times, the percentiles by nearest rank and the
    mean summed in the order given: the columns of the study's timing*.csv files, which sum in the
    order of instances.csv. None when empty."""
    if not values:
        return None
    total = 0.0
    for v in values:  # left to right, as the study sums (sum() compensates from Python 3.12 on)
        total += v
    return (len(values), percentile(values, 10), percentile(values, 50), percentile(values, 90),
            total / len(values), max(values))


def ns_tex(ns):
    """A time in nanoseconds for a LaTeX table or text, three significant digits above 1 us."""
    if ns is None or math.isnan(ns) or ns <= 0:
        return "--"
    if ns < 1000:
        return f"{ns:.0f}\\,ns"
    if ns < 1e6:
        return f"{ns / 1000:.3g}" + "\\,\\ensuremath{\\mu}s"
    return f"{ns / 1e6:.3g}\\,ms"


def split_method(m):
    """A method's algorithm and number type: "eberly_triangle/gmpfr<113>" -> ("eberly_triangle",
    "gmpfr<113>"); ("name", "") for a method without a number type (a judged program)."""
    base, _, nt = m.partition("/")
    return base, nt


def method_label(m):
    base, nt = split_method(m)
    if base.endswith("_as_written"):
        base = base[: -len("_as_written")] + " (as written)"
    return f"{base}, {nt.replace('_', ' ')}" if nt else base


def html_table(header, rows, row_classes=None, numeric=()):
    """An HTML <table> (a string) of `header` (column names) and `rows` (lists of cells), every
    cell escaped; row_classes[i] (optional) is the class of row i, and the columns named in
    `numeric` are right-aligned (class "num")."""
    attrs = [' class="num"' if h in numeric else "" for h in header]
    out = ["<table>", "<thead><tr>" + "".join(f"<th{a}>{escape(str(h))}</th>" for a, h in zip(attrs, header)) + "</tr></thead>", "<tbody>"]
    for k, row in enumerate(rows):
        cls = row_classes[k] if row_classes else ""
        tr = f'<tr class="{escape(cls)}">' if cls else "<tr>"
        out.append(tr + "".join(f"<td{a}>{escape(str(c))}</td>" for a, c in zip(attrs, row)) + "</tr>")
    out += ["</tbody>", "</table>"]
    return "\n".join(out)
