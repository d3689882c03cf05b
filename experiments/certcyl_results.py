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
  upper_median, percentile
  OUTCOMES, FAILURES      the study's outcome names; those counted as failures (FP + FN)
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
