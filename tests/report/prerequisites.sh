# Sourced by the report tests (run_report_test.sh, run_judge_report_test.sh): exits 77 (skipped)
# when /usr/bin/python3 has no matplotlib, with the reason given as $1; fails when matplotlib is
# there but Chromium is not (scripts/install-deps.sh --study installs both); else sets $chromium.
if ! /usr/bin/python3 -c 'import matplotlib, numpy' 2> /dev/null; then
  echo "skipped: /usr/bin/python3 has no matplotlib, $1 (bash scripts/install-deps.sh --study)"
  exit 77
fi
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
  echo "FAILED: Chromium is not installed, but matplotlib is: the packages of scripts/install-deps.sh --study are"
  echo "only partly installed; run  bash scripts/install-deps.sh --study  (it installs the Debian package chromium)"
  exit 1
fi
