#!/usr/bin/env bash
#SBATCH --job-name=certcyl-crosscheck-merge
# Combines the reports of a cross-check run as N shards (crosscheck.sbatch; the driver has no
# merge of its own), as a batch job after the array or by hand:
#   experiments/slurm/crosscheck-merge.sh DIR N
# Reads DIR/shard-K-of-N.txt for K = 0..N-1 and checks that every shard reported and exited 0,
# and that the shards belong together: per query one seed, and case ranges that follow each
# other without gap or overlap. Prints, per query, the driver's counts summed over the shards
# (cases, answers re-checked, separated/touching/overlapping, undecided, wrong, crashes), the
# range and seed, the CPU and wall seconds summed and the cases per CPU second (per core), then
# every failure line the shards printed; writes the same to DIR/summary.txt. Exit status 0 only
# when all N shards are there, each exited 0 and nothing was wrong, undecided or crashed.
set -euo pipefail
if [ $# -ne 2 ] || ! [[ "$2" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: crosscheck-merge.sh DIR N   (DIR holds shard-K-of-N.txt, K = 0..N-1)" >&2
  exit 2
fi
dir=$1
n=$2
[ -d "$dir" ] || { echo "crosscheck-merge: no folder $dir" >&2; exit 1; }
reports=()
indices=()
problems=()
missing=""
for ((k = 0; k < n; ++k)); do
  report="$dir/shard-$k-of-$n.txt"
  if [ ! -f "$report" ]; then
    missing+="${missing:+, }$k"
    continue
  fi
  status=$(tail -n 1 "$report" | sed -n 's/^exit \([0-9][0-9]*\)$/\1/p')
  [ "$status" = 0 ] || problems+=("shard $k of $n exited ${status:-without a status line} ($report)")
  reports+=("$report")
  indices+=("$k")
done
[ -z "$missing" ] || problems=("missing shard(s) $missing of $n in $dir (a task killed or never run: resubmit those indices)" "${problems[@]}")

summary=""
if [ ${#reports[@]} -gt 0 ]; then
  summary=$(awk -v indices="${indices[*]}" '
    BEGIN { split(indices, index_of_file, " "); file = 0 }
    FNR == 1 { k = index_of_file[++file]; q = "" }
    /^(line|triangle|cylinder): [0-9]+ cases, / {
      q = $1; sub(/:$/, "", q)
      if (!(q in shards)) order[++queries] = q
      shards[q]++
      cases[q] += $2; checked[q] += $4
      split($9, by, "/"); sep[q] += by[1]; touch[q] += by[2]; over[q] += by[3]
      undecided[q] += $11; wrong[q] += $13; crashes[q] += $15
      next
    }
    /^  seed [0-9]+, cases [0-9]+ to [0-9]+, / && q != "" {
      seed = $2 + 0
      if (!((q, "seed") in first)) { first[q, "seed"] = seed; first[q, "shard"] = k }
      else if (seed != first[q, "seed"]) bad = bad q ": seed " seed " in shard " k " but " first[q, "seed"] " in shard " first[q, "shard"] "\n"
      begin[q, k] = $4 + 0; end[q, k] = $6 + 0
      wall[q] += $9; cpu[q] += $12; if ($9 > slowest[q]) slowest[q] = $9
      q = ""
      next
    }
    /^  / { failures = failures "shard " k ": " substr($0, 3) "\n" }
    END {
      for (i = 1; i <= queries; ++i) {
        q = order[i]
        if (shards[q] != file) bad = bad q ": reported by " shards[q] " of " file " shards\n"
        previous = ""
        for (f = 1; f <= file; ++f) {
          k = index_of_file[f]
          if (!((q, k) in begin)) continue
          if (previous != "" && begin[q, k] != end[q, previous] + 1)
            bad = bad q ": shard " k " starts at case " begin[q, k] ", shard " previous " ended at " end[q, previous] "\n"
          if (previous == "") low = begin[q, k]
          previous = k
        }
        printf "%s: %d cases, %d certified answers re-checked; separated/touching/overlapping %d/%d/%d; undecided %d; wrong %d; crashes %d\n",
               q, cases[q], checked[q], sep[q], touch[q], over[q], undecided[q], wrong[q], crashes[q]
        printf "  seed %d, cases %d to %d in %d shards; %.1f s CPU and %.1f s wall summed, slowest shard %.1f s wall; %.1f cases per CPU second\n",
               first[q, "seed"], low, end[q, previous], shards[q], cpu[q], wall[q], slowest[q], (cpu[q] > 0 ? cases[q] / cpu[q] : 0)
        if (undecided[q] + wrong[q] + crashes[q] > 0) bad = bad q ": " wrong[q] " wrong, " undecided[q] " undecided, " crashes[q] " crashes\n"
      }
      if (queries == 0) bad = bad "no query counts in the reports\n"
      printf "%s", failures
      if (bad != "") { printf "%s", bad; exit 1 }
    }' "${reports[@]}") || problems+=("the counts of the shards do not add up to a clean run (above)")
fi
{
  [ -z "$summary" ] || echo "$summary"
  for p in "${problems[@]}"; do echo "crosscheck-merge: $p"; done
  if [ ${#problems[@]} -eq 0 ]; then
    echo "crosscheck-merge: $n of $n shards, all exited 0"
  fi
} | tee "$dir/summary.txt"
[ ${#problems[@]} -eq 0 ]
