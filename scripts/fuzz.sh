#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) under AddressSanitizer and UndefinedBehaviorSanitizer
# (scripts/build-sanitize.sh: clang, build-sanitize/, shared with scripts/test-sanitizers.sh) and
# runs each for the given time from its seed corpus (fuzz/corpus/<harness>/, copied, so the
# repository's corpus is left unchanged).
#   scripts/fuzz.sh [seconds]     default 60 s per harness
# Then the cylinder-pair harness again, for CERTCYL_FUZZ_PAIR_SECONDS (default 5 times the
# given time), from the corpus the sanitised run left, in a second build (build-fuzz/: clang -O2,
# UndefinedBehaviorSanitizer and libFuzzer without AddressSanitizer, assertions on), one process
# per core (CERTCYL_FUZZ_PAIR_WORKERS, default nproc) sharing the corpus directory (each reloads
# what the others add), each with its own log and random seed: each of its inputs runs two exact
# queries and their exact re-checks, so the sanitised build reaches a few thousand inputs a
# minute and this one several times more per process.
# Prints the executions per harness (summed over the processes) and its slowest input over 10 s; exits
# non-zero if a harness found a crash, a hang (one input over 10 s; 600 s for cylinder pairs), a
# memory blow-up, a leak, undefined behaviour, a wrong certified answer or an undecided cylinder
# pair (the input is kept in build-sanitize/findings/ or build-fuzz/findings/). Inputs over 10 s
# are kept there too (slow-unit-*), as measurements: the cost of a pair is not a pass/fail
# criterion here (bench/ measures it), only an input that looks like a hang is.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
harnesses=(fuzz_json_line fuzz_line_cylinder fuzz_triangle_cylinder fuzz_cylinder_cylinder fuzz_study_config fuzz_merge)
bash scripts/build-sanitize.sh "${harnesses[@]}"
build=build-sanitize
mkdir -p "$build/findings"
status=0
summary=()
# run HARNESS BUILD CORPUS SECONDS [PROCESSES]: one harness run (PROCESSES of them at once on the
# same corpus, default 1, logs HARNESS.log or HARNESS.<k>.log); the executions of all go to the
# summary.
run() {
  local h="$1" build="$2" work="$3" seconds="$4" processes="${5:-1}"
  # -timeout: one input taking longer than 10 s is a hang (600 s for the cylinder pairs, which
  # run without a resource limit: the fuzzer's hardest pairs, overlaps 2^-1000 thin beside
  # numbers spanning hundreds of binades, are decided by the complete arbitrary-precision stage
  # at 2,048 bits and more, in seconds, and over a minute on a loaded machine under the
  # sanitizers; bench/RESULTS.md); -rss_limit_mb: a memory blow-up.
  local timeout=10
  [ "$h" = fuzz_cylinder_cylinder ] && timeout=600
  local logs=() pids=() k
  for ((k = 1; k <= processes; ++k)); do
    local log="$build/$h.log"
    [ "$processes" -gt 1 ] && log="$build/$h.$k.log"
    logs+=("$log")
    "$build/fuzz/$h" "$work" -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=4096 -reload=1 \
      -artifact_prefix="$build/findings/$h-" -print_final_stats=1 > "$log" 2>&1 &
    pids+=($!)
  done
  local total=0 counted=1 runs slowest=0 t
  for k in "${!pids[@]}"; do
    local log="${logs[$k]}"
    if ! wait "${pids[$k]}"; then
      status=1
      echo "fuzz: $h FAILED (log $log):"
      grep -m 20 -E "ERROR|WRONG|UNDECIDED|SUMMARY|runtime error|Test unit written" "$log" || tail -20 "$log"
    fi
    runs=$(grep -m1 -oE "stat::number_of_executed_units: *[0-9]+" "$log" | grep -oE "[0-9]+$" || true)
    if [ -n "$runs" ]; then total=$((total + runs)); else counted=0; fi
    t=$(grep -m1 -oE "stat::slowest_unit_time_sec: *[0-9]+" "$log" | grep -oE "[0-9]+$" || true)
    if [ -n "$t" ] && [ "$t" -gt "$slowest" ]; then slowest=$t; fi
  done
  [ "$counted" = 1 ] || total="? (a process printed no count; at least $total)"
  local each=""
  [ "$processes" -gt 1 ] && each=" ($processes processes)"
  # libFuzzer records an input's time only above -report_slow_units (10 s by default).
  local slow="no input over 10 s"
  if [ "$slowest" -gt 0 ]; then slow="slowest input ${slowest} s"; fi
  summary+=("$h ($build): $total executions in ${seconds} s$each, $slow")
}
for h in "${harnesses[@]}"; do
  work="$build/corpus/$h"
  rm -rf "$work" && mkdir -p "$work" && cp fuzz/corpus/"$h"/* "$work"/
  run "$h" "$build" "$work" "$seconds"
done
# The cylinder-pair harness without AddressSanitizer, from the corpus of the run above.
fast=build-fuzz
pair_seconds="${CERTCYL_FUZZ_PAIR_SECONDS:-$((5 * seconds))}"
cmake -S . -B "$fast" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="-fsanitize=undefined,fuzzer-no-link -fno-sanitize-recover=all -fno-omit-frame-pointer -O2 -g1" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=undefined" -DCERTCYL_SANITIZE=ON -DCERTCYL_FUZZ=ON -DCERTCYL_FUZZ_SANITIZE=undefined \
  -DCERTCYL_BUILD_BENCHMARKS=OFF -DCERTCYL_BUILD_EXPERIMENTS=OFF -DCERTCYL_WERROR=ON > /dev/null
time cmake --build "$fast" -j"$(nproc)" --target fuzz_cylinder_cylinder
mkdir -p "$fast/findings"
work="$fast/corpus/fuzz_cylinder_cylinder"
rm -rf "$work" && mkdir -p "$work" && cp "$build/corpus/fuzz_cylinder_cylinder"/* "$work"/
run fuzz_cylinder_cylinder "$fast" "$work" "$pair_seconds" "${CERTCYL_FUZZ_PAIR_WORKERS:-$(nproc)}"
printf 'fuzz: %s\n' "${summary[@]}"
exit $status
