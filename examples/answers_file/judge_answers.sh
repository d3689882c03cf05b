#!/bin/sh
# The answers-file flow of `certcyl judge`: certcyl writes the cases, your method answers them
# wherever and however it runs (another machine, a batch job, a GPU), and certcyl scores the
# answers file. Run it in an empty folder:
#
#   sh judge_answers.sh [CERTCYL] [QUERY]        (defaults: certcyl, ray_cylinder)
#
# 1. cases.jsonl: one `certcyl query` line per case, with "meta" holding its family, the
#    certified answer and the certified gap (what your method must not read); then the cells of
#    the query's failure maps (--map-cells 16: 16 x 16 inputs 1 ulp apart around a degeneracy).
# 2. mine.jsonl: one line per case, in any order: {"id": "<the case's id>", "answer": A}, A one
#    of separated, touching, overlapping, intersecting (for a method that cannot tell touching),
#    undecided, error; other members are ignored (so `certcyl query`'s output is an answers file).
#    Here the method is examples/exec_python/line_double.py, run over the whole file at once.
# 3. results/mine/: families.csv, counterexamples.jsonl, answers.jsonl, summary.txt, the maps
#    (failure_maps.csv, failure_maps/) and the one-page report index.html.
set -e
CERTCYL=${1:-certcyl}
QUERY=${2:-ray_cylinder}
PYTHON=${PYTHON:-python3}
HERE=$(cd "$(dirname "$0")" && pwd)

"$CERTCYL" cases --query "$QUERY" --size tiny --map-cells 16 > cases.jsonl
"$PYTHON" "$HERE/../exec_python/line_double.py" < cases.jsonl > mine.jsonl
"$CERTCYL" judge --cases cases.jsonl --answers mine.jsonl --name mine
