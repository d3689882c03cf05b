#!/usr/bin/env bash
# The cross-check driver (experiments/crosscheck.cpp) built with assertions on: no NDEBUG, so
# CGAL's assertions, preconditions and postconditions are checked (a failing one throws, and the
# driver counts it as a crash), and libstdc++'s assertions (_GLIBCXX_ASSERTIONS: bounds of
# vectors and arrays, optional access). -O2, in build-assert/, only the driver is built.
#   scripts/crosscheck.sh [crosscheck options]   e.g. --query cylinder --cases 1000000 --threads 2
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build=build-assert
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O2 -g1 -D_GLIBCXX_ASSERTIONS" \
  -DCERTCYL_BUILD_TOOLS=OFF -DCERTCYL_BUILD_TESTS=OFF -DCERTCYL_BUILD_BENCHMARKS=OFF -DCERTCYL_WERROR=ON > /dev/null
cmake --build "$build" -j"$(nproc)" --target crosscheck
"$build/experiments/crosscheck" "$@"
