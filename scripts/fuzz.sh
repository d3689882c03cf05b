#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) under AddressSanitizer and UndefinedBehaviorSanitizer
# (scripts/build-sanitize.sh: clang, build-sanitize/, shared with scripts/test-sanitizers.sh) and
# runs each for the given time from its seed corpus (fuzz/corpus/<harness>/, copied, so the
# repository's corpus is left unchanged).
#   scripts/fuzz.sh [seconds]     default 60 s per harness
# Prints the executions per harness; exits non-zero if a harness found a crash, a hang (one
# input over 10 s; 60 s for cylinder pairs), a memory blow-up, a leak, undefined behaviour, a
# wrong certified answer or an undecided cylinder pair (the input is kept in
# build-sanitize/findings/).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
harnesses=(fuzz_json_line fuzz_line_cylinder fuzz_triangle_cylinder fuzz_cylinder_cylinder fuzz_study_config fuzz_merge)
bash scripts/build-sanitize.sh "${harnesses[@]}"
build=build-sanitize
mkdir -p "$build/findings"
status=0
summary=()
for h in "${harnesses[@]}"; do
  work="$build/corpus/$h"
  rm -rf "$work" && mkdir -p "$work" && cp fuzz/corpus/"$h"/* "$work"/
  log="$build/$h.log"
  # -timeout: one input taking longer than 10 s is a hang (60 s for the cylinder pairs, which run
  # without a resource limit: a pair spanning two thousand binades can take seconds under the
  # sanitizers); -rss_limit_mb: a memory blow-up.
  timeout=10
  [ "$h" = fuzz_cylinder_cylinder ] && timeout=60
  if ! "$build/fuzz/$h" "$work" -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=4096 \
      -artifact_prefix="$build/findings/$h-" -print_final_stats=1 > "$log" 2>&1; then
    status=1
    echo "fuzz: $h FAILED (log $log):"
    grep -m 20 -E "ERROR|WRONG|UNDECIDED|SUMMARY|runtime error|Test unit written" "$log" || tail -20 "$log"
  fi
  runs=$(grep -m1 -oE "stat::number_of_executed_units: *[0-9]+" "$log" | grep -oE "[0-9]+$" || echo "?")
  summary+=("$h: $runs executions in ${seconds} s")
done
printf 'fuzz: %s\n' "${summary[@]}"
exit $status
