#!/usr/bin/env bash
# The test suite: install what is needed (with the peer libraries, matplotlib and LaTeX, so
# that the study and paper tests run), build everything warning-clean, run ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --study --paper
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCERTCYL_WERROR=ON
cmake --build build -j"$(nproc)"
cd build
ctest -j"$(nproc)" --output-on-failure --timeout 900
