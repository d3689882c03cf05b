#!/bin/bash
# `certcyl judge --study`: the judged method's point on a study's speed-against-error figures.
#   run_judge_study_test.sh CERTCYL STUDY_DIR WORK_DIR
# Judges `certcyl query --method shene --nt double` through --exec at --size tiny with the study
# of STUDY_DIR (the one `ctest -R report` writes) and checks: exit status 0; the figures and their
# page in the judge's results (figures/pareto.png, figures/index.html naming the judged method
# and the caveat of a judged time, manifest.json listing the judge's speed.csv); the study's
# folder byte for byte unchanged (the star's position on the figures is checked by
# check_plot_judged.py, on plot_study.py --judged itself). Then the errors: a
# folder that is not a study, --study with an answers file, --study with --shard (exit status 1,
# the message naming the option). Exit status 77 (skipped) without matplotlib.
set -u
certcyl=$(realpath "$1") study=$(realpath "$2") work=$3
/usr/bin/python3 -c 'import matplotlib' 2>/dev/null || { echo "skipped: /usr/bin/python3 has no matplotlib"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail=0
problem() { echo "FAIL: $*"; fail=1; }
snapshot() { (cd "$study" && find . -type f | sort | xargs sha256sum); }
before=$(snapshot)
label="shene double (judged)"
"$certcyl" judge --exec "$certcyl query --method shene --nt double" --label "$label" --query line_cylinder --size tiny \
  --study "$study" --out results --name j > out.txt 2> err.txt
status=$?
[ $status -eq 0 ] || problem "exit status $status: $(tail -3 err.txt)"
grep -q "^figures: results/j/figures " out.txt || problem "no figures line in the summary: $(tail -3 out.txt)"
for f in pareto.png pareto.pdf pareto_compact.png index.html manifest.json; do
  [ -s "results/j/figures/$f" ] || problem "results/j/figures/$f missing"
done
grep -q "shene double (judged)" results/j/figures/index.html || problem "the figures' page does not name the judged method"
grep -q "mean per query" results/j/figures/index.html || problem "the figures' page lacks the judged time's caveat"
grep -q "results/j/speed.csv\|j/speed.csv" results/j/figures/manifest.json || problem "the manifest does not list the judge's speed.csv"
[ "$(snapshot)" = "$before" ] || problem "the study's folder changed"
expect_error() {  # expect_error MESSAGE ARGS...: exit status 1 and MESSAGE on standard error
  local message=$1; shift
  "$certcyl" judge "$@" --out results --name e > /dev/null 2> e.txt
  local s=$?
  [ $s -eq 1 ] || problem "judge $*: exit status $s (expected 1)"
  grep -qF -- "$message" e.txt || problem "judge $*: '$message' not in: $(cat e.txt)"
}
"$certcyl" cases --query line_cylinder --size tiny > cases.jsonl
"$certcyl" query --method shene --nt double < cases.jsonl > answers.jsonl
expect_error "--study: '$work' is not a study's results folder (no summary.csv)" --exec "$certcyl query" --query line_cylinder --size tiny --study "$work"
expect_error "--study: needs --exec or --plugin" --answers answers.jsonl --cases cases.jsonl --study "$study"
expect_error "--study: not with --shard" --exec "$certcyl query" --query line_cylinder --size tiny --study "$study" --shard 0/2
[ $fail -eq 0 ] && echo "judge --study: ok"
exit $fail
