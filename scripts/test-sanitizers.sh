#!/usr/bin/env bash
# The tests labelled 'sanitize' (tests/CMakeLists.txt) under AddressSanitizer and
# UndefinedBehaviorSanitizer, in build-asan/ (g++; any report fails the run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build=build-asan
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCERTCYL_SANITIZE=ON -DCERTCYL_WERROR=ON \
  -DCERTCYL_BUILD_BENCHMARKS=OFF -DCERTCYL_BUILD_EXPERIMENTS=OFF > /dev/null
cmake --build "$build" -j"$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$build"
ctest -j"$(nproc)" -L sanitize --output-on-failure --timeout 900
