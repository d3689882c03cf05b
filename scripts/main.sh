#!/usr/bin/env bash
# The main job on its built-in default: install what is needed (with the peer libraries and
# matplotlib), build, and run the robustness study (`certcyl study`, results in results/).
# Extra arguments go to the certcyl command instead (for example `demo`, or `study --size small`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --study
mkdir -p build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build/configure.log 2>&1 \
  || { cat build/configure.log; exit 1; }
cmake --build build -j"$(nproc)" --target certcyl_cli
if [ $# -eq 0 ]; then set -- study; fi
exec ./build/bin/certcyl "$@"
