#!/usr/bin/env bash
# ctest 'report': a tiny study with its figures, then its page results/tiny/index.html checked
# as a reader gets it: rendered by headless Chromium in a tall window, the screenshot not blank
# (the summary at the top, figures below), every image and link the page names present, every
# figure shown with a caption and no larger than a page, the summary table the rows of
# summary.csv (tests/report/check_report.py); and the study's standard error names each figure
# as it is plotted.
#   run_report_test.sh CERTCYL_BINARY SOURCE_DIR WORK_DIR
# Exit status 77 (skipped) when /usr/bin/python3 has no matplotlib (then the study draws no
# figures). Chromium missing where matplotlib is installed is a failure: scripts/install-deps.sh
# --study installs both (python3-matplotlib and chromium), as scripts/test.sh does.
set -euo pipefail
certcyl=$1
src=$2
work=$3

# shellcheck source=prerequisites.sh
source "$src/tests/report/prerequisites.sh" "so the study draws no figures"

rm -rf "$work"
mkdir -p "$work"
"$certcyl" study --size tiny --seed 1 --threads 2 --out "$work" --name tiny > "$work/study.out" 2> "$work/study.err" ||
  { cat "$work/study.out" "$work/study.err"; echo "FAILED: the study failed"; exit 1; }
dir=$work/tiny
grep -qx "report: $dir/index.html" "$work/study.out" || { cat "$work/study.out"; echo "FAILED: standard output does not name the report"; exit 1; }

# Progress: one line per figure on standard error.
figures=$(find "$dir/figures" -name '*.png' | wc -l)
lines=$(grep -c '^plot_study: [0-9]* figures, ' "$work/study.err" || true)
[ "$figures" -gt 0 ] && [ "$lines" -eq "$figures" ] ||
  { cat "$work/study.err"; echo "FAILED: $figures figures but $lines progress lines on standard error"; exit 1; }

# Headless Chromium: the page in a window tall enough for the summary and the first figures.
timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --user-data-dir="$work/chromium" \
  --screenshot="$work/page.png" --window-size=1280,12000 "file://$dir/index.html" > "$work/chromium.log" 2>&1 ||
  { cat "$work/chromium.log"; echo "FAILED: Chromium could not render index.html"; exit 1; }
[ -s "$work/page.png" ] || { cat "$work/chromium.log"; echo "FAILED: Chromium wrote no screenshot"; exit 1; }
/usr/bin/python3 "$src/tests/report/check_report.py" "$dir" "$work/page.png"
echo "report test: index.html rendered and checked, $figures figures"
