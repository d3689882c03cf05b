#!/usr/bin/env bash
# ctest 'paper': runs a tiny study, builds the paper against it (paper/build.sh, which ends with
# paper/check_paper.py: every included table and figure exists and was generated from this
# study's files, the PDF exists with a plausible page count), then shows that the checker
# rejects a paper whose figure is missing, one without the table of errors against k, one whose
# table of errors against k shows a count other than instances.csv's, and one whose figures are
# stale, and one whose timing table or paired table of the seeds shows a count other than
# instances.csv's, or whose table of the uniform sample shows a count other than uniform.csv's,
# and one with a table wider than the text, and one quoting a count as a share of another unit's.
#   run_paper_test.sh CERTCYL_BINARY SOURCE_DIR WORK_DIR
set -euo pipefail
certcyl=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
"$certcyl" study --size tiny --seed 1 --out "$work" --name tiny --no-plots --threads 2 > "$work/study.log"
bash "$src/paper/build.sh" --lenient "$work/tiny" "$work/paper"

check() { /usr/bin/python3 "$src/paper/check_paper.py" "$@"; }

# A figure the paper includes, deleted after the build: the check must fail.
figure=$(sed 's/%.*//' "$src/paper/paper.tex" | grep -o 'figures/[^}]*\.pdf' | head -n 1)
[ -n "$figure" ] || { echo "paper.tex includes no figure"; exit 1; }
cp -a "$work/paper" "$work/missing"
rm "$work/missing/$figure"
if check "$work/missing" "$work/tiny" > "$work/missing.log"; then
  echo "FAILED: a missing $figure was not detected"; exit 1
fi
grep -q "missing: $figure" "$work/missing.log" || { cat "$work/missing.log"; echo "FAILED: no 'missing' report"; exit 1; }

# The errors against k: a paper.tex that leaves out their table must fail, and so must a table
# whose counts differ from instances.csv even where its manifest entry was updated to match.
cp -a "$work/paper" "$work/noktable"
sed -i '/generated\/tables\/error_by_k/d' "$work/noktable/paper.tex"
if check "$work/noktable" "$work/tiny" > "$work/noktable.log"; then
  echo "FAILED: a paper without the table of errors against k was accepted"; exit 1
fi
grep -q "^check_paper: paper.tex does not include generated/tables/error_by_k.tex" "$work/noktable.log" \
  || { cat "$work/noktable.log"; echo "FAILED: no report of the missing table of errors against k"; exit 1; }
cp -a "$work/paper" "$work/recount"
/usr/bin/python3 - "$work/recount/generated" <<'PY'
import hashlib, json, re, sys
gen = sys.argv[1]
path = gen + "/tables/error_by_k.tex"
lines = open(path).read().split("\n")
i = next(k for k, l in enumerate(lines) if l.startswith("% error_by_k: ")) + 1
lines[i] = re.sub(r"& (\d+)/(\d+)", lambda m: f"& {m.group(1)}/{int(m.group(2)) + 1}", lines[i], count=1)
open(path, "w").write("\n".join(lines))
man = json.load(open(gen + "/manifest.json"))
man["outputs"]["tables/error_by_k.tex"] = hashlib.sha256(open(path, "rb").read()).hexdigest()
json.dump(man, open(gen + "/manifest.json", "w"), indent=1, sort_keys=True)
PY
touch "$work/recount/paper.pdf"
if check "$work/recount" "$work/tiny" > "$work/recount.log"; then
  echo "FAILED: a table of errors against k with a wrong count was accepted"; exit 1
fi
grep -q "^check_paper: generated/tables/error_by_k.tex: .* instances.csv gives" "$work/recount.log" \
  || { cat "$work/recount.log"; echo "FAILED: no report of the wrong count"; exit 1; }

# The timing table and the paired table of the seeds: a time or a paired count other than what
# instances.csv gives (the manifest updated to match) must fail, naming the table.
tamper() {  # tamper DIR TABLE MARKER: the line after the first MARKER line gets its last number changed
  /usr/bin/python3 - "$1/generated" "$2" "$3" <<'PY2'
import hashlib, json, re, sys
gen, table, marker = sys.argv[1:]
path = f"{gen}/tables/{table}"
lines = open(path).read().split("\n")
i = next(k for k, l in enumerate(lines) if l.startswith(marker)) + 1
lines[i] = re.sub(r"& (\d+) &", lambda m: f"& {int(m.group(1)) + 1} &", lines[i], count=1)
open(path, "w").write("\n".join(lines))
man = json.load(open(gen + "/manifest.json"))
man["outputs"]["tables/" + table] = hashlib.sha256(open(path, "rb").read()).hexdigest()
json.dump(man, open(gen + "/manifest.json", "w"), indent=1, sort_keys=True)
PY2
  touch "$1/paper.pdf"
}
for t in "timing_certified.tex:% timing: :instances.csv" "seeds_by_type.tex:% paired: :instances.csv" \
         "uniform_sample.tex:% uniform: :uniform.csv"; do
  table=${t%%:*}
  source_file=${t##*:}
  t=${t%:*}
  cp -a "$work/paper" "$work/tamper"
  tamper "$work/tamper" "$table" "${t#*:}"
  if check "$work/tamper" "$work/tiny" > "$work/tamper.log"; then
    echo "FAILED: a wrong count in $table was accepted"; exit 1
  fi
  grep -q "^check_paper: generated/tables/$table: .* $source_file gives" "$work/tamper.log" \
    || { cat "$work/tamper.log"; echo "FAILED: no report of the wrong count in $table"; exit 1; }
  rm -rf "$work/tamper"
done

# A table wider than the text: paper.tex with one more table 1.1 text widths wide, set by
# pdflatex (its log reports the overfull box); the check must fail, naming it.
cp -a "$work/paper" "$work/wide"
sed -i 's/^\\end{document}/\\begin{table}[p]\\begin{tabular}{@{}l@{}}\\rule{1.1\\textwidth}{1pt}\\end{tabular}\\end{table}\n\\end{document}/' "$work/wide/paper.tex"
grep -q '^\\begin{table}\[p\]\\begin{tabular}' "$work/wide/paper.tex" || { echo "FAILED: the wide table was not added"; exit 1; }
(cd "$work/wide" && pdflatex -interaction=nonstopmode paper.tex > pdflatex.log 2>&1) || true
if check "$work/wide" "$work/tiny" > "$work/wide.log"; then
  echo "FAILED: a table wider than the text was accepted"; exit 1
fi
grep -q '^check_paper: LaTeX: Overfull \\hbox' "$work/wide.log" || { cat "$work/wide.log"; echo "FAILED: no report of the overfull table"; exit 1; }

# A count quoted as a share of a count of another unit (methods of searches): the check must
# fail, naming both.
cp -a "$work/paper" "$work/units"
printf '%s\n' '\stat{hunt:methodswrong} of the \stat{hunt:searches} searches' >> "$work/units/paper.tex"
if check "$work/units" "$work/tiny" > "$work/units.log"; then
  echo "FAILED: a count of methods quoted as a share of searches was accepted"; exit 1
fi
grep -q '^check_paper: paper.tex: .stat{hunt:methodswrong} of .stat{hunt:searches} compares methods with searches' "$work/units.log" \
  || { cat "$work/units.log"; echo "FAILED: no report of the mixed units"; exit 1; }

# Stale figures: another study (a different seed) replaces the results, the tables are
# regenerated from it but the figures are not: the check must fail on the figures.
"$certcyl" study --size tiny --seed 2 --out "$work" --name tiny2 --no-plots --threads 2 > "$work/study2.log"
cp -a "$work/paper" "$work/stale"
/usr/bin/python3 "$src/paper/make_tables.py" "$work/tiny2" "$work/stale/generated" > /dev/null
if check "$work/stale" "$work/tiny2" > "$work/stale.log"; then
  echo "FAILED: stale figures were not detected"; exit 1
fi
grep -q "^check_paper: figures: stale" "$work/stale.log" || { cat "$work/stale.log"; echo "FAILED: no 'stale' report for the figures"; exit 1; }
if grep -q "^check_paper: generated: stale" "$work/stale.log"; then
  cat "$work/stale.log"; echo "FAILED: the regenerated tables were reported stale"; exit 1
fi
echo "paper test: built, checked, and the checker rejects a missing and a stale figure, a paper without the errors against k, and a wrong count in their table, the timing table, the paired table or the uniform sample's table, a table wider than the text and a count quoted as a share of another unit's"
