#!/usr/bin/env bash
# Whether two study results folders hold the same CSV files with the same rows, but for the
# timing columns (instances.csv `ns`, summary.csv `median_ns`, the timing*.csv percentiles and
# means: measured, so they differ between any two runs; their counts `n` must agree) and
# timing_thread.csv (which CPU each shard's timing thread was pinned to: one row per shard, so a
# merged study has more rows than an unsharded one):
#   tests/slurm/compare_study.sh REFERENCE OTHER
# Every *.csv under REFERENCE (instances, inputs, hunt, summary, summary_families, failure maps)
# must exist under OTHER, and OTHER must have no CSV file that REFERENCE lacks (the shard-*
# folders of a merged study aside). Prints the rows
# compared per file, or the first differences, and exits 1 on any difference.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: compare_study.sh REFERENCE OTHER" >&2; exit 2; }
reference=$1
other=$2
timing_columns="ns median_ns p10_ns p50_ns p90_ns mean_ns max_ns"

# The file without the timing columns, found by name in its header line.
untimed() {
  awk -F, -v drop="$timing_columns" '
    BEGIN { n = split(drop, names, " "); for (i = 1; i <= n; ++i) dropped_name[names[i]] = 1 }
    NR == 1 { for (i = 1; i <= NF; ++i) if ($i in dropped_name) skip[i] = 1 }
    {
      line = ""; first = 1
      for (i = 1; i <= NF; ++i) if (!(i in skip)) { line = line (first ? "" : ",") $i; first = 0 }
      print line
    }' "$1"
}

# The CSV files of a results folder, but not those of the shards a merged folder keeps, nor
# timing_thread.csv.
listing() { (cd "$1" && find . -path './shard-*' -prune -o -name '*.csv' ! -name timing_thread.csv -type f -print | sort); }
status=0
if ! diff <(listing "$reference") <(listing "$other") > /dev/null; then
  echo "compare_study: the CSV files differ (< $reference, > $other):"
  diff <(listing "$reference") <(listing "$other") || true
  status=1
fi
[ "$(listing "$reference" | wc -l)" -gt 0 ] || { echo "compare_study: no CSV files in $reference"; exit 1; }
while read -r file; do
  [ -f "$other/$file" ] || continue
  if differences=$(diff <(untimed "$reference/$file") <(untimed "$other/$file")); then
    echo "compare_study: ${file#./}: $(($(wc -l < "$reference/$file") - 1)) rows equal"
  else
    echo "compare_study: ${file#./} differs (< $reference, > $other):"
    head -n 20 <<< "$differences"
    status=1
  fi
done < <(listing "$reference")
exit "$status"
