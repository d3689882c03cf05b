#!/usr/bin/env bash
# The main job on its built-in default: install what is needed, build, run.
# Extra arguments go to the certcyl command (default: `demo`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
mkdir -p build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build/configure.log 2>&1 \
  || { cat build/configure.log; exit 1; }
cmake --build build -j"$(nproc)" --target certcyl_cli
if [ $# -eq 0 ]; then set -- demo; fi
exec ./build/bin/certcyl "$@"
