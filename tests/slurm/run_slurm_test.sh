#!/usr/bin/env bash
# The batch scripts of experiments/slurm/ on a real Slurm: a private single-node cluster on this
# machine (scripts/slurm-local.sh, as root), stopped on exit whatever happens.
#   tests/slurm/run_slurm_test.sh CERTCYL CROSSCHECK SOURCE_DIR WORK_DIR
# 1. A tiny study as an array job of 4 shards: task 2 fails (killed by SIGKILL as it starts),
#    task 3 is cancelled with scancel while it runs. The merge job (afterok) must not run, and
#    `certcyl merge` must refuse, naming shards 2 and 3. Resubmitting indices 2 and 3 alone, with
#    their own merge job, completes the study, and the merged CSV files must equal an unsharded
#    run of the same configuration, row for row, but for the timing columns
#    (tests/slurm/compare_study.sh).
# 2. The cross-check, every query at 120 cases, as 3 array tasks of 2 CPUs (so 2 threads; 1 on
#    a node of one CPU) each and the merge job: the summed counts must equal an unsharded run's,
#    line for line. Then the same submitted held and task 2 cancelled before it runs: the merge
#    job (afterany) must fail, naming the missing shard.
# 3. A judgement (`certcyl query --method shene --nt double` as --exec, line_cylinder at size
#    tiny): the cases job writes the cases certcyl cases writes, then 3 array tasks, task 1 failing
#    (killed as it starts): the merge job (afterok) must not run and judge-merge.sh must refuse,
#    naming shard 1. Re-submitting index 1 alone (no new cases job: the file exists) completes the
#    merge, whose families.csv, counterexamples.jsonl and answers.jsonl must equal an unsharded
#    judgement's byte for byte.
# Every wait has a time limit; exit 77 (skipped) when not root or Slurm is not installed.
set -euo pipefail
[ $# -eq 4 ] || { echo "usage: run_slurm_test.sh CERTCYL CROSSCHECK SOURCE_DIR WORK_DIR" >&2; exit 2; }
certcyl=$(realpath "$1")
crosscheck=$(realpath "$2")
source_dir=$(realpath "$3")
work=$(realpath -m "$4")
submit=$source_dir/experiments/slurm/submit.sh

if [ "$(id -u)" -ne 0 ]; then
  echo "slurm test: skipped (the private cluster's daemons run as root)"
  exit 77
fi
for program in munged slurmctld slurmd sbatch; do
  command -v "$program" > /dev/null || { echo "slurm test: skipped ($program not installed: scripts/install-deps.sh --slurm)"; exit 77; }
done

cluster=$work/cluster
stop_cluster() { bash "$source_dir/scripts/slurm-local.sh" stop "$cluster" || true; }
stop_cluster  # daemons left by a run that was killed before its trap ran
rm -rf "$work"
mkdir -p "$work"
trap stop_cluster EXIT
trap 'exit 1' INT TERM
# Every wait ends by this deadline, well before the test's 900 s limit in ctest.
deadline=$((SECONDS + 720))
remaining() { echo $((deadline - SECONDS > 1 ? deadline - SECONDS : 1)); }
timeout 90 bash "$source_dir/scripts/slurm-local.sh" start "$cluster"
export SLURM_CONF=$cluster/slurm.conf

fail() {
  echo "slurm test: FAILED: $*" >&2
  local log
  for log in "$cluster"/log/slurm*.log; do echo "--- $log" >&2; tail -n 20 "$log" >&2; done
  exit 1
}

# The states of a job's records (one per array task), e.g. "COMPLETED COMPLETED CANCELLED".
job_states() {
  scontrol -o show job "$1" 2> /dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | tr '\n' ' ' | sed 's/ $//'
}
# Waits until no record of the job is pending, running or completing; fails after $2 seconds
# or at the deadline.
wait_job() {
  local id=$1 limit=$2 states=""
  [ "$limit" -le "$(remaining)" ] || limit=$(remaining)
  local end=$((SECONDS + limit))
  while [ "$SECONDS" -lt "$end" ]; do
    states=$(job_states "$id")
    if [ -n "$states" ] && ! [[ " $states " =~ \ (PENDING|RUNNING|CONFIGURING|COMPLETING|SUSPENDED|REQUEUED)\  ]]; then
      echo "$states"
      return
    fi
    sleep 0.5
  done
  squeue >&2 || true
  scontrol show job "$id" >&2 || true
  fail "job $id not finished within $limit s (states: $states)"
}
# Runs submit.sh with the given settings; sets array_id, merge_id and cases_id (a judge's cases
# job, when one was submitted; else empty).
submit() {
  local ids
  ids=$(env "$@" timeout 60 bash "$submit" "$kind" "${sbatch_options[@]}") || fail "submit.sh $kind failed"
  cases_id=""
  read -r array_id merge_id cases_id <<< "$ids"
  [[ "$array_id" =~ ^[0-9]+$ && "$merge_id" =~ ^[0-9]+$ && "$cases_id" =~ ^[0-9]*$ ]] ||
    fail "submit.sh printed '$ids', not two job ids (and a cases job's)"
}

# --- 1. The study: a lost shard, its re-run, the merge against an unsharded run.
results=$work/results
timeout "$(remaining)" "$certcyl" study --size tiny --threads 2 --out "$results" --name unsharded --no-plots --no-progress > "$work/unsharded.txt" ||
  fail "the unsharded study failed"
# certcyl, but while the marker exists the task of shard 2 of 4 kills itself (SIGKILL) as it
# starts, and that of shard 3 waits (until the test cancels it).
lost=$work/lose-shards-2-and-3
wrapper=$work/certcyl-losing-shards-2-and-3
cat > "$wrapper" << EOF
#!/usr/bin/env bash
if [ -e '$lost' ]; then
  [[ " \$* " == *" --shard 2/4 "* ]] && kill -KILL \$\$
  [[ " \$* " == *" --shard 3/4 "* ]] && exec sleep 120
fi
exec '$certcyl' "\$@"
EOF
chmod +x "$wrapper"
touch "$lost"
study_settings=(CERTCYL_BIN="$wrapper" CERTCYL_OUT="$results" CERTCYL_NAME=sharded CERTCYL_SIZE=tiny CERTCYL_SHARDS=4 CERTCYL_PLOTS=0)
kind=study
sbatch_options=()
submit "${study_settings[@]}"
task_state() { scontrol -o show job "${array_id}_$1" 2> /dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }
end=$((SECONDS + 120))
until [ "$(task_state 3)" = RUNNING ]; do
  [ "$SECONDS" -lt "$end" ] || fail "task 3 not running within 120 s"
  sleep 0.2
done
scancel "${array_id}_3" || fail "scancel ${array_id}_3"
states=$(wait_job "$array_id" 300)
echo "study array job $array_id: $states"
[ "$(task_state 2)" = FAILED ] || fail "task 2 is $(task_state 2), not FAILED"
[ "$(task_state 3)" = CANCELLED ] || fail "task 3 is $(task_state 3), not CANCELLED"
[ "$(task_state 0) $(task_state 1)" = "COMPLETED COMPLETED" ] || fail "tasks 0 and 1 did not complete ($states)"
merge_state=$(wait_job "$merge_id" 120)
echo "study merge job $merge_id after task 2 failed and task 3 was cancelled: $merge_state"
[ "$merge_state" = CANCELLED ] || fail "the merge job ran ($merge_state) although tasks 2 and 3 did not complete"
[ ! -e "$results/sharded/instances.csv" ] || fail "a merged instances.csv exists although shards 2 and 3 are missing"
if refused=$(timeout "$(remaining)" "$certcyl" merge "$results/sharded" --no-plots 2>&1); then
  fail "certcyl merge accepted the shards without shards 2 and 3: $refused"
fi
[[ "$refused" == *"missing shard(s) 2, 3 of 4"* ]] || fail "certcyl merge did not name shards 2 and 3: $refused"
echo "certcyl merge refused: $refused"

rm "$lost"
submit "${study_settings[@]}" CERTCYL_TASKS=2,3
states=$(wait_job "$array_id" 300)
merge_state=$(wait_job "$merge_id" 300)
echo "re-run of shards 2 and 3: array job $array_id $states, merge job $merge_id $merge_state"
if [ "$states" != "COMPLETED COMPLETED" ] || [ "$merge_state" != COMPLETED ]; then
  fail "the re-run of shards 2 and 3 or its merge did not complete"
fi
bash "$source_dir/tests/slurm/compare_study.sh" "$results/unsharded" "$results/sharded" ||
  fail "the merged shards differ from the unsharded study"

# --- 2. The cross-check: summed counts against an unsharded run; a missing shard reported.
timeout "$(remaining)" "$crosscheck" --query all --cases 120 --threads 2 > "$work/crosscheck-unsharded.txt" || fail "the unsharded cross-check failed"
kind=crosscheck
crosscheck_settings=(CERTCYL_CROSSCHECK="$crosscheck" CERTCYL_OUT="$results" CERTCYL_QUERY=all CERTCYL_CASES=120 CERTCYL_SHARDS=3)
sbatch_options=()
cpus=$(sinfo -h -o %c | head -n 1)
[ "$cpus" -ge 2 ] && cpus=2
submit "${crosscheck_settings[@]}" CERTCYL_NAME=crosscheck CERTCYL_CPUS="$cpus"
states=$(wait_job "$array_id" 300)
merge_state=$(wait_job "$merge_id" 120)
echo "cross-check array job $array_id: $states; merge job $merge_id: $merge_state"
if [ "$states" != "COMPLETED COMPLETED COMPLETED" ] || [ "$merge_state" != COMPLETED ]; then fail "the cross-check jobs did not complete"; fi
counts() { grep -E '^(line|triangle|cylinder): ' "$1"; }
if ! diff <(counts "$work/crosscheck-unsharded.txt") <(counts "$results/crosscheck/summary.txt"); then
  fail "the cross-check's shards summed differ from the unsharded run (above)"
fi
[ "$(counts "$results/crosscheck/summary.txt" | wc -l)" -eq 3 ] || fail "the merged cross-check lacks a query"
grep -q '^  seed 3, cases 0 to 119 in 3 shards;' "$results/crosscheck/summary.txt" || fail "the merged cylinder range is not cases 0 to 119"
# Each task ran the driver with its SLURM_CPUS_PER_TASK threads, for each of the three queries.
for report in "$results"/crosscheck/shard-{0,1,2}-of-3.txt; do
  [ "$(grep -c ", $cpus thread(s), " "$report")" -eq 3 ] || fail "$report: not $cpus thread(s) for each query (CERTCYL_CPUS=$cpus)"
done

sbatch_options=(--hold)
submit "${crosscheck_settings[@]}" CERTCYL_NAME=crosscheck-lost
scancel "${array_id}_2" || fail "scancel ${array_id}_2"
scontrol release "$array_id" "$merge_id" || fail "scontrol release"
wait_job "$array_id" 300 > /dev/null
merge_state=$(wait_job "$merge_id" 120)
echo "cross-check merge job $merge_id after a cancelled task: $merge_state"
[ "$merge_state" = FAILED ] || fail "the cross-check merge job did not fail ($merge_state) with shard 2 missing"
grep -q "missing shard(s) 2 of 3" "$results/crosscheck-lost/summary.txt" || fail "the cross-check merge did not name shard 2"
# --- 3. The judge: a cases job, the array of 3 shards after it, the merge; a lost shard re-run.
# certcyl, but while the marker exists the task of shard 1 of 3 kills itself as it starts.
cat > "$wrapper" << EOF
#!/usr/bin/env bash
[ -e '$lost' ] && [[ " \$* " == *" --shard 1/3 "* ]] && kill -KILL \$\$
exec '$certcyl' "\$@"
EOF
timeout "$(remaining)" "$certcyl" cases --query line_cylinder --size tiny > "$work/judge-cases.jsonl" || fail "certcyl cases failed"
method="$certcyl query --method shene --nt double"
timeout "$(remaining)" "$certcyl" judge --cases "$work/judge-cases.jsonl" --exec "$method" --label shene \
  --out "$results" --name judge-unsharded > /dev/null || fail "the unsharded judgement failed"
kind=judge
judge_settings=(CERTCYL_BIN="$wrapper" CERTCYL_OUT="$results" CERTCYL_NAME=judge CERTCYL_QUERY=line_cylinder
  CERTCYL_SIZE=tiny CERTCYL_SHARDS=3 CERTCYL_EXEC="$method" CERTCYL_LABEL=shene CERTCYL_TIMEOUT=60)
sbatch_options=()
touch "$lost"
submit "${judge_settings[@]}"
[ -n "$cases_id" ] || fail "no cases job submitted although $results/judge/cases.jsonl did not exist"
[ "$(wait_job "$cases_id" 120)" = COMPLETED ] || fail "the cases job $cases_id did not complete"
cmp -s "$work/judge-cases.jsonl" "$results/judge/cases.jsonl" || fail "the cases job's cases differ from certcyl cases'"
states=$(wait_job "$array_id" 300)
merge_state=$(wait_job "$merge_id" 120)
echo "judge array job $array_id: $states; merge job $merge_id: $merge_state"
[ "$(task_state 1)" = FAILED ] || fail "judge task 1 is $(task_state 1), not FAILED"
[ "$(task_state 0) $(task_state 2)" = "COMPLETED COMPLETED" ] || fail "judge tasks 0 and 2 did not complete ($states)"
[ "$merge_state" = CANCELLED ] || fail "the judge's merge job ran ($merge_state) although task 1 failed"
for k in 0 2; do
  [ -f "$results/judge/shard-$k-of-3/answers.jsonl" ] || fail "shard $k of 3 is not in place"
done
if refused=$(CERTCYL_BIN="$certcyl" timeout 60 bash "$source_dir/experiments/slurm/judge-merge.sh" "$results/judge" 3 2>&1); then
  fail "judge-merge.sh merged without shard 1: $refused"
fi
[[ "$refused" == *"missing shard(s) 1 of 3"* ]] || fail "judge-merge.sh did not name shard 1: $refused"
echo "judge-merge.sh refused: $refused"
rm "$lost"
submit "${judge_settings[@]}" CERTCYL_TASKS=1
[ -z "$cases_id" ] || fail "a cases job was submitted again although the cases file exists"
states=$(wait_job "$array_id" 300)
merge_state=$(wait_job "$merge_id" 120)
echo "re-run of judge shard 1: array job $array_id $states, merge job $merge_id $merge_state"
[ "$states $merge_state" = "COMPLETED COMPLETED" ] || fail "the re-run of judge shard 1 or its merge did not complete"
# The merged judgement is the unsharded one, file for file (summary.txt names its own folder).
for f in families.csv counterexamples.jsonl answers.jsonl; do
  cmp "$results/judge-unsharded/$f" "$results/judge/$f" || fail "the merged judgement's $f differs from the unsharded run's"
done
[ "$(head -n 1 "$results/judge/summary.txt")" = "$(head -n 1 "$results/judge-unsharded/summary.txt")" ] ||
  fail "the merged summary's first line differs from the unsharded run's"
[ "$(wc -l < "$results/judge/answers.jsonl")" -eq "$(wc -l < "$work/judge-cases.jsonl")" ] ||
  fail "the merged answers.jsonl does not answer every case"
echo "slurm test: passed"
