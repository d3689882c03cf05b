#!/usr/bin/env bash
#SBATCH --job-name=certcyl-judge-merge
# Merges the shards of a judgement (judge.sbatch), as a batch job after the array or by hand:
#   experiments/slurm/judge-merge.sh DIR N [CASES]
# Every shard DIR/shard-K-of-N (K = 0..N-1) must be there, finished (renamed from
# shard-K-of-N.partial when all its cases were judged), and judged by the same method (the first
# line of its summary.txt). Their answers.jsonl, concatenated, are judged with
# `certcyl judge --cases CASES --answers ... --label METHOD` into DIR itself (CASES default
# DIR/cases.jsonl; the program is CERTCYL_BIN, default certcyl on PATH): the same
# families.csv, counterexamples.jsonl and answers.jsonl as an unsharded run on the same cases,
# and its summary. The answers file refuses a case answered twice, a case of no shard and an
# answer to no case. Exit status 0 only when all N shards are merged.
set -euo pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ] || ! [[ "$2" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: judge-merge.sh DIR N [CASES]   (DIR holds shard-K-of-N, K = 0..N-1)" >&2
  exit 2
fi
dir=${1%/}
n=$2
cases=${3:-$dir/cases.jsonl}
certcyl=${CERTCYL_BIN:-certcyl}
[ -d "$dir" ] || { echo "judge-merge: no folder $dir" >&2; exit 1; }
[ -f "$cases" ] || { echo "judge-merge: no cases file $cases" >&2; exit 1; }

missing=""
unfinished=""
method=""
for ((k = 0; k < n; ++k)); do
  shard="$dir/shard-$k-of-$n"
  if [ ! -f "$shard/answers.jsonl" ] || [ ! -f "$shard/summary.txt" ]; then
    if [ -d "$shard.partial" ]; then unfinished+="${unfinished:+, }$k"; else missing+="${missing:+, }$k"; fi
    continue
  fi
  # "certcyl judge: METHOD, J of C cases judged"
  this=$(sed -n '1s/^certcyl judge: \(.*\), [0-9]* of [0-9]* cases judged$/\1/p' "$shard/summary.txt")
  [ -n "$this" ] || { echo "judge-merge: $shard/summary.txt does not name the judged method" >&2; exit 1; }
  if [ -z "$method" ]; then
    method=$this
    first=$k
  elif [ "$this" != "$method" ]; then
    echo "judge-merge: shard $k of $n judged '$this', shard $first '$method': not one judgement" >&2
    exit 1
  fi
done
if [ -n "$missing$unfinished" ]; then
  [ -z "$missing" ] || echo "judge-merge: missing shard(s) $missing of $n in $dir (a task killed or never run: resubmit those indices)" >&2
  [ -z "$unfinished" ] || echo "judge-merge: unfinished shard(s) $unfinished of $n in $dir (shard-K-of-$n.partial: the task failed, see its summary.txt; resubmit those indices)" >&2
  exit 1
fi

answers=$dir/shards-answers.jsonl.part
trap 'rm -f "$answers"' EXIT
for ((k = 0; k < n; ++k)); do cat "$dir/shard-$k-of-$n/answers.jsonl"; done > "$answers"
"$certcyl" judge --cases "$cases" --answers "$answers" --label "$method" \
  --out "$(dirname "$dir")" --name "$(basename "$dir")"
echo "judge-merge: $n of $n shards merged into $dir"
