#!/usr/bin/env bash
# The tests labelled 'sanitize' (tests/CMakeLists.txt) under AddressSanitizer and
# UndefinedBehaviorSanitizer, built by scripts/build-sanitize.sh (clang, build-sanitize/).
# Any sanitizer report, leak or failed assertion fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build-sanitize.sh sanitize_tests
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd build-sanitize
time ctest -j"$(nproc)" -L sanitize --output-on-failure --timeout 900
