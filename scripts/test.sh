#!/usr/bin/env bash
# The test suite: install what is needed (with the peer libraries, matplotlib, LaTeX and Slurm,
# so that the study, paper and Slurm tests run), build everything warning-clean, run ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --study --paper --slurm
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCERTCYL_WERROR=ON
cmake --build build -j"$(nproc)"
cd build
ctest -j"$(nproc)" --output-on-failure --timeout 900
