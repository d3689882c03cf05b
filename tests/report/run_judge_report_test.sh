#!/usr/bin/env bash
# ctest 'judge_report': the page of `certcyl judge`, results/<name>/index.html, checked as a
# reader gets it (tests/report/check_judge_report.py):
#   1. the example plugin (naive double tests, failing near tangency and the caps) judged at
#      --size tiny: standard output names the page; the page states families.csv's counts and
#      Wilson intervals and shows min(5, counterexamples) counterexamples, each drawn in inline
#      SVG; rendered by headless Chromium, the DOM holds the drawings and the screenshot is not
#      blank and shows one drawing per counterexample;
#   2. the certified answers judged as a method's: the page states no failure and shows no figure.
#   run_judge_report_test.sh CERTCYL_BINARY PLUGIN SOURCE_DIR WORK_DIR
# Exit status 77 (skipped) when /usr/bin/python3 has no matplotlib and numpy (the screenshot is
# read with them). Chromium missing where they are installed is a failure: scripts/install-deps.sh
# --study installs both (python3-matplotlib and chromium), as scripts/test.sh does.
set -euo pipefail
certcyl=$1
plugin=$2
src=$3
work=$4
check=$src/tests/report/check_judge_report.py

# shellcheck source=prerequisites.sh
source "$src/tests/report/prerequisites.sh" "needed to read the screenshot"

rm -rf "$work"
mkdir -p "$work"

# 1. A method with failures.
"$certcyl" judge --plugin "$plugin" --size tiny --out "$work" --name plugin > "$work/judge.out" 2> "$work/judge.err" ||
  { cat "$work/judge.out" "$work/judge.err"; echo "FAILED: certcyl judge failed"; exit 1; }
dir=$work/plugin
grep -qx "report: $dir/index.html" "$work/judge.out" || { cat "$work/judge.out"; echo "FAILED: standard output does not name the report"; exit 1; }
[ "$(grep -c . "$dir/counterexamples.jsonl")" -gt 0 ] || { echo "FAILED: the plugin has no counterexample"; exit 1; }

browse() {  # browse OUTPUT_OPTION: headless Chromium on the page, in a tall window
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --user-data-dir="$work/chromium" \
    --window-size=1280,9000 "$@" "file://$dir/index.html"
}
browse --screenshot="$work/page.png" > "$work/chromium.log" 2>&1 ||
  { cat "$work/chromium.log"; echo "FAILED: Chromium could not render index.html"; exit 1; }
[ -s "$work/page.png" ] || { cat "$work/chromium.log"; echo "FAILED: Chromium wrote no screenshot"; exit 1; }
browse --dump-dom > "$work/dom.html" 2> "$work/chromium-dom.log" ||
  { cat "$work/chromium-dom.log"; echo "FAILED: Chromium could not dump the DOM of index.html"; exit 1; }
/usr/bin/python3 "$check" "$dir" "$work/page.png" "$work/dom.html"

# 2. A method without failures: the certified answers themselves.
"$certcyl" cases --query segment_cylinder --size tiny > "$work/cases.jsonl"
/usr/bin/python3 -c '
import json, sys
for l in open(sys.argv[1]):
    c = json.loads(l)
    print(json.dumps({"id": c["id"], "answer": c["meta"]["certified"]}))' "$work/cases.jsonl" > "$work/certified.jsonl"
"$certcyl" judge --cases "$work/cases.jsonl" --answers "$work/certified.jsonl" --out "$work" --name certified > "$work/certified.out" ||
  { cat "$work/certified.out"; echo "FAILED: certcyl judge of the certified answers failed"; exit 1; }
grep -q "id=\"verdict\"><b>0 failures</b>" "$work/certified/index.html" || { echo "FAILED: the page of the certified answers does not open on 0 failures"; exit 1; }
/usr/bin/python3 "$check" "$work/certified"
echo "judge report test: index.html rendered and checked"
