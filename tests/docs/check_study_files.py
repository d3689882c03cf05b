#!/usr/bin/env python3
"""ctest 'study_files_doc': experiments/STUDY_FILES.md documents the files the study writes.

Runs a small study (every method, two families, 4x4 failure maps) and checks, against that
results folder:
  - every CSV file of the folder (failure_maps/*.csv as failure_maps/NAME.csv) has a section
    in the document, and every section a file;
  - each CSV header is exactly the documented column list, in order (a failure map's header:
    the documented columns, then one column per method);
  - each failure map's JSON holds exactly the documented keys, in order;
  - the documented cell codes are exactly the codes the JSON's "codes" names, and every cell of
    every map holds a documented code.

  check_study_files.py CERTCYL_BINARY SOURCE_DIR WORK_DIR
"""
import csv
import json
import pathlib
import re
import shutil
import subprocess
import sys

certcyl, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
doc_path = source / "experiments" / "STUDY_FILES.md"
failures = []


def fail(message):
    failures.append(message)
    print("FAILED:", message)


# The document: "## `FILE`" (or "## Cell codes") sections, each with a table whose first
# column holds the names in backticks.
sections = {}
current = None
for line in doc_path.read_text().splitlines():
    heading = re.match(r"^## (?:`([^`]+)`|(.+))$", line)
    if heading:
        current = heading.group(1) or heading.group(2).strip()
        sections[current] = []
        continue
    row = re.match(r"^\| `([^`]+)` \|", line)
    if row and current is not None:
        sections[current].append(row.group(1))

# The results of a small study.
if work.exists():
    shutil.rmtree(work)
work.mkdir(parents=True)
(work / "config.json").write_text(
    json.dumps({"per_family": 1, "map_cells": 4, "hunt_evaluations": 2, "families": ["c_cap_cap", "tangent_rotated"]}))
run = subprocess.run([certcyl, "study", "--config", str(work / "config.json"), "--out", str(work), "--name", "s",
                      "--no-plots", "--no-progress", "--threads", "2"], capture_output=True, text=True, timeout=300)
if run.returncode != 0:
    print(run.stdout, run.stderr)
    sys.exit("FAILED: the study failed")
results = work / "s"

written = {p.relative_to(results).as_posix() for p in results.glob("*.csv")}
maps = sorted((results / "failure_maps").glob("*.csv"))
if not maps:
    fail("the study wrote no failure map")
written |= {"failure_maps/NAME.csv", "failure_maps/NAME.json"}
documented = {name for name in sections if name.endswith(".csv") or name.endswith(".json")}
for name in sorted(written - documented):
    fail(f"{name} is written but has no section in {doc_path.name}")
for name in sorted(documented - written):
    fail(f"{doc_path.name} documents {name}, which the study does not write")


def header(path):
    with open(path, newline="") as f:
        return next(csv.reader(f))


for name in sorted(written & documented):
    if name.startswith("failure_maps/"):
        continue
    got = header(results / name)
    if got != sections[name]:
        fail(f"{name}: the header is {','.join(got)}\n  {doc_path.name} lists {','.join(sections[name])}")

fixed = sections.get("failure_maps/NAME.csv", [])
keys = sections.get("failure_maps/NAME.json", [])
codes = sections.get("Cell codes", [])
if not fixed or not keys or not codes:
    fail(f"{doc_path.name} lacks the failure map columns, the JSON keys or the cell codes")
methods_seen = set()
for path in maps:
    got = header(path)
    if got[:len(fixed)] != fixed:
        fail(f"{path.name}: the header starts {','.join(got[:len(fixed)])}; documented: {','.join(fixed)}")
    methods = got[len(fixed):]
    methods_seen.update(methods)
    if not methods or any("/" not in m for m in methods):
        fail(f"{path.name}: the columns after {fixed[-1]} are not method names: {','.join(methods)}")
    meta = json.loads(path.with_suffix(".json").read_text())
    if list(meta) != keys:
        fail(f"{path.stem}.json: the keys are {', '.join(meta)}; documented: {', '.join(keys)}")
    named = re.findall(r"(?:^|, )(\S) ", meta.get("codes", ""))
    if sorted(named) != sorted(codes):
        fail(f"{path.stem}.json names the codes {' '.join(named)}; documented: {' '.join(codes)}")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))[1:]
    if len(rows) != 16:
        fail(f"{path.name}: {len(rows)} rows for 4x4 cells")
    for row in rows:
        certified = row[fixed.index("certified")]
        if certified not in ("s", "t", "o", "u"):
            fail(f"{path.name}: certified code {certified!r}")
        for code in row[len(fixed):]:
            if code not in codes:
                fail(f"{path.name}: cell code {code!r} is not documented")
                break

if failures:
    sys.exit(f"FAILED: {len(failures)} difference(s) between {doc_path.name} and the study's files")
print(f"{doc_path.name}: {len(written)} files, {len(maps)} failure maps, {len(methods_seen)} methods checked")
