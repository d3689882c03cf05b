#!/usr/bin/env bash
# The paper, from a fresh clone: install the packages (with the peer libraries, matplotlib and
# LaTeX), build the certcyl command, run the default study (`certcyl study`) into results/paper,
# generate the tables, quoted numbers and figures from its CSV files, and build the PDF.
#   bash scripts/paper.sh               the default study, then the paper
#   bash scripts/paper.sh RESULTS_DIR   the paper of an existing results folder (no study run)
# The PDF is build/paper/paper.pdf; everything generated stays under build/paper/.
set -euo pipefail
given=""
if [ $# -ge 1 ]; then given=$(realpath -m "$1"); fi
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --study --paper
if [ -n "$given" ]; then
  results=$given
  [ -f "$results/instances.csv" ] || { echo "paper.sh: $results has no instances.csv (not a study results folder)" >&2; exit 2; }
else
  mkdir -p build
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build/configure.log 2>&1 \
    || { cat build/configure.log; exit 1; }
  cmake --build build -j"$(nproc)" --target certcyl_cli
  ./build/bin/certcyl study --name paper --no-plots
  results=results/paper
fi
bash paper/build.sh "$results" build/paper
