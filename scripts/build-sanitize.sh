#!/usr/bin/env bash
# The sanitizer build shared by scripts/test-sanitizers.sh and scripts/fuzz.sh: clang in
# build-sanitize/, every translation unit under AddressSanitizer and UndefinedBehaviorSanitizer
# (no recovery: the first report aborts), with libFuzzer's coverage instrumentation
# (fuzzer-no-link; outside a fuzz harness its hooks are no-ops), -O1 -g1 (line numbers in the
# reports; a third of the cost of -O2 -g to build). Only the tests labelled 'sanitize', the
# library certcyl_query they and fuzz_json_line need, and the fuzz harnesses are configured.
#   scripts/build-sanitize.sh TARGET...    builds the given targets (sanitize_tests, fuzz_*)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --fuzz
build=build-sanitize
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=all -fno-omit-frame-pointer -O1 -g1"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCERTCYL_SANITIZE=ON -DCERTCYL_FUZZ=ON \
  -DCERTCYL_BUILD_BENCHMARKS=OFF -DCERTCYL_BUILD_EXPERIMENTS=OFF -DCERTCYL_WERROR=ON > /dev/null
time cmake --build "$build" -j"$(nproc)" --target "$@"
