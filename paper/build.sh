#!/usr/bin/env bash
# Builds the paper against a study results folder (scripts/paper.sh is the one-command entry).
#   bash paper/build.sh [--lenient] RESULTS_DIR OUT_DIR
# --lenient: a number the text quotes but the study did not produce (a method without instances
# in some family, as in `certcyl study --size tiny`) prints as [?] with a warning instead of
# stopping LaTeX; without it such a number is an error.
# OUT_DIR/generated   tables and quoted numbers (paper/make_tables.py, from the CSV files)
# OUT_DIR/figures     figures (experiments/plot_study.py, from the CSV files)
# OUT_DIR/paper.pdf   the paper (latexmk), then checked by paper/check_paper.py
set -euo pipefail
pretex=()
if [ "${1:-}" = "--lenient" ]; then
  pretex=(-usepretex='\def\statlenient{}')
  shift
fi
[ $# -eq 2 ] || { echo "usage: paper/build.sh RESULTS_DIR OUT_DIR" >&2; exit 2; }
src=$(cd "$(dirname "$0")/.." && pwd)
results=$(realpath "$1")
out=$(realpath -m "$2")
for tool in latexmk pdflatex bibtex pdfinfo; do
  command -v "$tool" > /dev/null || { echo "paper/build.sh: $tool not found (bash scripts/install-deps.sh --paper)" >&2; exit 2; }
done
rm -rf "$out/generated" "$out/figures"
mkdir -p "$out"
/usr/bin/python3 "$src/paper/make_tables.py" "$results" "$out/generated"
/usr/bin/python3 "$src/experiments/plot_study.py" "$results" --out "$out/figures"
cp "$src/paper/paper.tex" "$src/paper/references.bib" "$out/"
rm -f "$out/paper.pdf"
if ! (cd "$out" && latexmk -pdf -interaction=nonstopmode -halt-on-error "${pretex[@]}" paper.tex > latexmk.log 2>&1); then
  tail -40 "$out/latexmk.log" >&2
  echo "paper/build.sh: LaTeX failed; the log is $out/paper.log" >&2
  exit 1
fi
/usr/bin/python3 "$src/paper/check_paper.py" "$out" "$results"
echo "paper: $out/paper.pdf"
