#!/usr/bin/python3
"""Checks that a built paper comes from the study outputs it claims to come from.

    /usr/bin/python3 paper/check_paper.py OUT_DIR RESULTS_DIR

OUT_DIR is where paper/build.sh built the paper (paper.tex, generated/, figures/, paper.pdf).
Fails (exit status 1, one line per problem) when
  - a file that paper.tex \\input's or \\includegraphics's is missing from OUT_DIR;
  - such a file is not an output listed in generated/manifest.json or figures/manifest.json,
    or its SHA-256 differs from the one recorded there (edited or replaced after generation);
  - a manifest records a study file (CSV or JSON) whose SHA-256 differs from the file now in
    RESULTS_DIR, or that is missing there (the table or figure is stale);
  - the manifests do not cover the study's main CSV files;
  - paper.tex quotes a count as a share of another ("\\stat{A} of \\stat{B}") whose unit in
    generated/units.json differs or is missing (searches of methods, answers of instances);
  - paper.tex does not include the errors against k (REQUIRED_INCLUDES), or a line of
    generated/tables/error_by_k.tex shows wrong/decided counts other than those recounted here from
    RESULTS_DIR/instances.csv (per bin of k, hard-case families, Boolean or three-valued);
  - a line of generated/tables/timing_certified.tex shows times (n, p10, p50, p90, mean, max)
    other than those recounted from instances.csv (per query, method and input class, or per
    deciding stage of the certified cylinder pairs, inputs.csv's stage column);
  - a line of generated/tables/seeds_by_type.tex shows a paired count or FP/FN/class counts other
    than those recounted on the instances where every number type of the algorithm ran;
  - a line of generated/tables/uniform_sample.tex shows decided answers, FP/FN/class or
    undecided counts other than RESULTS_DIR/uniform.csv's for its query and method, or its line
    of the other methods lists a method with a wrong answer, leaves one out or gives another
    least decided count, or the table leaves out a query of uniform.csv;
  - paper.pdf is missing, older than a file it includes, or has an implausible page count
    (pdfinfo), or the LaTeX log reports undefined references or citations, or a box (a table,
    a line) wider than the text by more than OVERFULL_PT.
"""
import csv
import json
import os
import re
import subprocess
import sys

# SHA-256 as make_tables.py and plot_study.py record it, from the module the scripts share.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments"))
import certcyl_results as cr  # noqa: E402
from certcyl_results import K_BINS, k_bin, sha256  # noqa: E402

# The appendix carries the full proofs (completeness, touching, the filters' error bounds, the
# signed gap): 32 pages against the default study, 31 against the tiny one at the time of
# writing, most of the body's length in the results' tables and figures; the limit leaves two
# pages for a study's longer tables and catches a runaway table or figure.
MIN_PAGES, MAX_PAGES = 6, 34
# The most a box may stick out into the margin (LaTeX's \hfuzz is 0.1pt; a visible overhang is
# a few points).
OVERFULL_PT = 1.0
REQUIRED_INPUTS = ["instances.csv", "inputs.csv", "summary.csv", "summary_families.csv", "hunt.csv", "uniform.csv"]
# What the results section must show: the errors per bin of k (findings on single rates).
REQUIRED_INCLUDES = ["generated/tables/error_by_k.tex", "figures/error_by_k.pdf", "generated/tables/timing_certified.tex",
                     "generated/tables/seeds_by_type.tex", "generated/tables/uniform_sample.tex"]
K_TABLE = "generated/tables/error_by_k.tex"
TIMING_TABLE = "generated/tables/timing_certified.tex"
SEEDS_TABLE = "generated/tables/seeds_by_type.tex"
UNIFORM_TABLE = "generated/tables/uniform_sample.tex"
WRONG = {"boolean": ("false_positive", "false_negative"), "three_valued": ("false_positive", "false_negative", "class_mismatch")}


def recount_by_k(instances):
    """(query, method) -> per bin of K_BINS and then over all k, [decided, Boolean wrong,
    three-valued wrong], recounted from instances.csv: hard-case families, decided answers."""
    counts = {}
    with open(instances, newline="") as f:
        for r in csv.DictReader(f):
            o = r["outcome"]
            if r["family"] == "uniform" or o not in ("agree", "false_positive", "false_negative", "class_mismatch"):
                continue
            c = counts.setdefault((r["query"], r["method"]), [[0, 0, 0] for _ in range(len(K_BINS) + 1)])
            for cell in (c[k_bin(r["k_ulps"])], c[-1]):
                cell[0] += 1
                cell[1] += o in WRONG["boolean"]
                cell[2] += o in WRONG["three_valued"]
    return counts


def table_cells(line):
    """The cells of a table line, its row end and spacing removed."""
    return [c.strip() for c in re.sub(r"\\\\(\[[^\]]*\])?\s*$", "", line).split("&")]


def check_marked_lines(path, table, pattern, recount, problems, none_found=None):
    """What the checks of the generated tables share: for every line of the table at `path`
    matching the regex `pattern` (a comment saying what the next line shows), recount(match,
    cells) gives the comparisons (what, shown, wanted, source) of the next line's cells
    (table_cells) with the study's file `source`; each whose shown cells are not the wanted ones
    is one problem, "TABLE: WHAT: shows ..., SOURCE gives ...". `none_found`, when given, is the
    problem when no line matches."""
    with open(path) as f:
        lines = f.read().splitlines()
    matched = 0
    for i, line in enumerate(lines):
        m = re.match(pattern, line)
        if not m:
            continue
        matched += 1
        cells = table_cells(lines[i + 1]) if i + 1 < len(lines) else []
        for what, shown, want, source in recount(m, cells):
            if shown != want:
                problems.append(f"{table}: {what}: shows {' '.join(shown)}, {source} gives {' '.join(want)}")
    if not matched and none_found:
        problems.append(f"{table}: {none_found}")


def check_k_table(path, instances, problems):
    """Every line of the table after a comment "% error_by_k: QUERY METHOD MEASURE" holds, per bin
    of k and over all k, the wrong answers over the decided ones that instances.csv gives."""
    counts = recount_by_k(instances)

    def recount(m, cells):
        q, method, measure = m.groups()
        c = counts.get((q, method))
        want = ["" if c is None or not cell[0] else f"{cell[2 if measure == 'three_valued' else 1]}/{cell[0]}"
                for cell in (c or [[0, 0, 0]] * (len(K_BINS) + 1))]
        return [(f"{q} {method} {measure}", cells[2:], want, "instances.csv")]
    check_marked_lines(path, K_TABLE, r"^% error_by_k: (\S+) (\S+) (boolean|three_valued)$", recount, problems, "no line of counts")


def check_timing_table(path, instances, inputs, problems):
    """Every line after "% timing: QUERY METHOD CLASS" or "% timing_stage: METHOD STAGE all" shows
    n, p10, p50, p90, mean and max of the times that instances.csv gives for it (a call that ended
    its process has none), formatted as the table formats them."""
    rows = cr.read_csv(instances)
    stage = {r["instance"]: r["stage"] for r in cr.read_csv(inputs)}

    def recount(m, cells):
        if m.group(1):
            q, method, cls = m.group(2, 3, 4)
            times = [float(r["ns"]) for r in rows if r["query"] == q and r["method"] == method and r["answer"] != "process_ended"
                     and cls in ("all", cr.input_class(r["family"]))]
            what = f"{q} {method} {cls}"
        else:
            method, st = m.group(5, 6)
            times = [float(r["ns"]) for r in rows if r["query"] == "cylinder_cylinder" and r["method"] == method
                     and r["answer"] != "process_ended" and stage.get(r["instance"]) == st]
            what = f"{method} stage {st}"
        stats = cr.time_stats(times)
        want = [] if stats is None else [str(stats[0])] + [cr.ns_tex(v) for v in stats[1:]]
        return [(what, cells[2:], want, "instances.csv")]
    check_marked_lines(path, TIMING_TABLE, r"^% (?:(timing): (\S+) (\S+) (generic|near_degenerate|all)|timing_stage: (\S+) (\S+) all)$",
                       recount, problems, "no line of times")


def check_seeds_table(path, instances, problems):
    """Every line after "% paired: BASE NT..." shows the instances where every number type of BASE
    ran (per query, pooled) and, per number type, FP/FN/class on those instances only."""
    rows = cr.read_csv(instances)
    ran = cr.ran_on(rows)

    def recount(m, cells):
        base, nts = m.group(1), m.group(2).split()
        common = {}
        for q in {q for q, _ in ran}:
            ms = [f"{base}/{nt}" for nt in nts if (q, f"{base}/{nt}") in ran]
            if ms:
                common[q] = cr.paired(rows, q, ms, ran)
        counts = {nt: [0, 0, 0, 0] for nt in nts}
        for r in rows:
            b, nt = cr.split_method(r["method"])
            if b == base and nt in counts and r["instance"] in common.get(r["query"], ()) and r["outcome"] != "uncertified":
                c = counts[nt]
                c[0] += 1
                c[1] += r["outcome"] == "false_positive"
                c[2] += r["outcome"] == "false_negative"
                c[3] += r["outcome"] == "class_mismatch"
        want = [str(sum(len(v) for v in common.values()))] + [f"{c[1]}/{c[2]}/{c[3]}" if c[0] else "" for c in counts.values()]
        return [(f"{base} on the paired instances", cells[1:], want, "instances.csv")]
    check_marked_lines(path, SEEDS_TABLE, r"^% paired: (\S+) (.*)$", recount, problems, "no line of counts")


def check_uniform_table(path, uniform, problems):
    """Every line after "% uniform: QUERY METHOD" shows that row of uniform.csv: decided, FP, FN,
    class, and undecided + error + invalid; every line after "% uniform_quiet: QUERY METHOD..."
    lists exactly the query's methods without a wrong answer or an undecided one and shows the
    least decided count among them; every query of uniform.csv is in the table."""
    rows = {(r["query"], r["method"]): r for r in cr.read_csv(uniform)}
    seen = set()

    def recount(m, cells):
        if m.group(1):
            q, method = m.group(2, 3)
            seen.add(q)
            r = rows.get((q, method))
            if r is None:
                problems.append(f"{UNIFORM_TABLE}: {q} {method} is not in uniform.csv")
                return []
            want = [r["decided"], r["false_positive"], r["false_negative"], r["class_mismatch"],
                    str(int(r["undecided"]) + int(r["error"]) + int(r["invalid"]))]
            return [(f"{q} {method}", cells[2:7], want, "uniform.csv")]
        q, listed = m.group(4), m.group(5).split()
        seen.add(q)
        clean = sorted(k[1] for k, r in rows.items() if k[0] == q and cr.uniform_errors(r).wrong3 == 0
                       and int(r["undecided"]) + int(r["error"]) + int(r["invalid"]) == 0)
        least = min((int(rows[(q, m)]["decided"]) for m in listed if (q, m) in rows), default=0)
        return [(f"{q}: the other methods", sorted(listed), clean, "uniform.csv"),
                (f"{q}: the other methods' wrong and undecided counts", cells[3:7], ["0"] * 4, "uniform.csv"),
                (f"{q}: the other methods' least decided count", cells[2:3], [f"$\\ge${least}"], "uniform.csv")]
    check_marked_lines(path, UNIFORM_TABLE, r"^% (?:(uniform): (\S+) (\S+)|uniform_quiet: (\S+) (.*))$", recount, problems)
    missing = sorted({q for q, _ in rows} - seen)
    if missing:
        problems.append(f"{UNIFORM_TABLE}: leaves out the queries {' '.join(missing)} of uniform.csv")


def check_count_units(tex, units, problems):
    """Every "\\stat{A} of \\stat{B}" (or "of the") in the text compares counts of one unit:
    both keys have a unit in generated/units.json (make_tables.py's COUNT_UNITS) and it is the
    same, so that searches are not quoted as a share of methods, nor answers of instances. A key
    the study did not produce is left to LaTeX (an error, or [?] in a lenient build)."""
    text = " ".join(re.sub(r"(?<!\\)%.*", "", line) for line in tex.splitlines())
    pairs = re.findall(r"\\stat\{([^}]*)\}\s+of\s+(?:the\s+)?\\stat\{([^}]*)\}", text)
    for a, b in pairs:
        if a not in units or b not in units:
            continue  # a number the study did not produce: LaTeX's error, or [?] in a lenient build
        ua, ub = units[a], units[b]
        if ua is None or ub is None or ua != ub:
            problems.append(f"paper.tex: \\stat{{{a}}} of \\stat{{{b}}} compares {ua or 'a count without a unit'} "
                            f"with {ub or 'a count without a unit'} (generated/units.json)")
    return len(pairs)


def included_files(tex):
    """Paths that the .tex includes: \\input{...} and \\includegraphics[...]{...}, comments removed."""
    text = "\n".join(re.sub(r"(?<!\\)%.*", "", line) for line in tex.splitlines())
    files = []
    for m in re.finditer(r"\\input\{([^}]+)\}", text):
        p = m.group(1)
        files.append(p if os.path.splitext(p)[1] else p + ".tex")
    for m in re.finditer(r"\\includegraphics(?:\[[^\]]*\])?\{([^}]+)\}", text):
        files.append(m.group(1))
    return files


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    out, res = sys.argv[1], sys.argv[2]
    problems = []
    with open(os.path.join(out, "paper.tex")) as f:
        tex = f.read()
    files = included_files(tex)
    if not files:
        problems.append("paper.tex includes no generated file")
    for rel in REQUIRED_INCLUDES:
        if rel not in files:
            problems.append(f"paper.tex does not include {rel}")
    upath = os.path.join(out, "generated", "units.json")
    if os.path.exists(upath):
        with open(upath) as f:
            check_count_units(tex, json.load(f), problems)
    else:
        problems.append("generated/units.json is missing")
    if os.path.exists(os.path.join(out, K_TABLE)) and os.path.exists(os.path.join(res, "instances.csv")):
        check_k_table(os.path.join(out, K_TABLE), os.path.join(res, "instances.csv"), problems)
    if os.path.exists(os.path.join(out, TIMING_TABLE)) and os.path.exists(os.path.join(res, "instances.csv")):
        check_timing_table(os.path.join(out, TIMING_TABLE), os.path.join(res, "instances.csv"), os.path.join(res, "inputs.csv"), problems)
    if os.path.exists(os.path.join(out, SEEDS_TABLE)) and os.path.exists(os.path.join(res, "instances.csv")):
        check_seeds_table(os.path.join(out, SEEDS_TABLE), os.path.join(res, "instances.csv"), problems)
    if os.path.exists(os.path.join(out, UNIFORM_TABLE)):
        if os.path.exists(os.path.join(res, "uniform.csv")):
            check_uniform_table(os.path.join(out, UNIFORM_TABLE), os.path.join(res, "uniform.csv"), problems)
        else:
            problems.append(f"{UNIFORM_TABLE}: {res} has no uniform.csv")

    # The manifests of the two generators, keyed by the subdirectory they describe.
    manifests = {}
    for sub in ("generated", "figures"):
        mpath = os.path.join(out, sub, "manifest.json")
        if not os.path.exists(mpath):
            problems.append(f"{sub}/manifest.json is missing")
            continue
        with open(mpath) as f:
            manifests[sub] = json.load(f)

    # Every study file a generator read must be unchanged in RESULTS_DIR.
    covered = set()
    for sub, man in manifests.items():
        for rel, digest in man.get("inputs", {}).items():
            covered.add(rel)
            p = os.path.join(res, rel)
            if not os.path.exists(p):
                problems.append(f"{sub}: read {rel}, which is not in {res}")
            elif sha256(p) != digest:
                problems.append(f"{sub}: stale, {rel} changed since it was generated")
    for sub in manifests:
        for rel in REQUIRED_INPUTS:
            if sub == "generated" and rel not in manifests[sub].get("inputs", {}):
                problems.append(f"{sub}: did not read {rel}")
    if "figures" in manifests and "instances.csv" not in manifests["figures"].get("inputs", {}):
        problems.append("figures: did not read instances.csv")

    # Every included file exists and is a recorded, unmodified output of a generator.
    newest = 0.0
    for rel in files:
        p = os.path.join(out, rel)
        if not os.path.exists(p):
            problems.append(f"missing: {rel} (included by paper.tex)")
            continue
        newest = max(newest, os.path.getmtime(p))
        sub, _, inner = rel.partition("/")
        man = manifests.get(sub)
        if man is None:
            problems.append(f"{rel}: not under generated/ or figures/, so not generated from the study")
            continue
        digest = man.get("outputs", {}).get(inner)
        if digest is None:
            problems.append(f"{rel}: not an output of {man.get('generator', sub)}")
        elif sha256(p) != digest:
            problems.append(f"{rel}: changed after it was generated")

    # The PDF.
    pdf = os.path.join(out, "paper.pdf")
    if not os.path.exists(pdf):
        problems.append("paper.pdf is missing")
    else:
        if os.path.getmtime(pdf) < newest:
            problems.append("paper.pdf is older than a file it includes")
        info = subprocess.run(["pdfinfo", pdf], capture_output=True, text=True)
        m = re.search(r"^Pages:\s+(\d+)", info.stdout, re.M)
        pages = int(m.group(1)) if m else 0
        if not MIN_PAGES <= pages <= MAX_PAGES:
            problems.append(f"paper.pdf has {pages} pages, expected {MIN_PAGES} to {MAX_PAGES}")
        log = os.path.join(out, "paper.log")
        if os.path.exists(log):
            with open(log, errors="replace") as f:
                text = f.read()
            for pat in (r"Reference `[^']*' on page \d+ undefined", r"Citation `[^']*' on page \d+ undefined"):
                for w in sorted(set(re.findall(pat, text))):
                    problems.append("LaTeX: " + w)
            # A table or a line wider than the text (LaTeX sets it anyway, into the margin).
            for w, where in re.findall(r"^Overfull \\hbox \((\d+(?:\.\d+)?)pt too wide\) (.*)$", text, re.M):
                if float(w) > OVERFULL_PT:
                    problems.append(f"LaTeX: Overfull \\hbox ({w}pt too wide) {where}")
        else:
            problems.append("paper.log is missing")

    if problems:
        for p in problems:
            print("check_paper: " + p)
        return 1
    print(f"check_paper: {len(files)} included files, all generated from {res}; paper.pdf has {pages} pages")
    return 0


if __name__ == "__main__":
    sys.exit(main())
