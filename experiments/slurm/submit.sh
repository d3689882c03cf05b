#!/usr/bin/env bash
# Submits a sharded run to Slurm: an array job, one shard per task (SLURM_ARRAY_TASK_ID is the
# shard), and a merge job that depends on it.
#   experiments/slurm/submit.sh study      [sbatch options]   certcyl study, then certcyl merge
#   experiments/slurm/submit.sh crosscheck [sbatch options]   the cross-check, then crosscheck-merge.sh
# The sbatch options (e.g. --partition=P --time=4:00:00, or --hold) go to both jobs; so do
# sbatch's own SBATCH_* variables. Settings, from the environment:
#   CERTCYL_BUILD    build folder holding bin/certcyl and experiments/crosscheck (default: build);
#                    CERTCYL_BIN and CERTCYL_CROSSCHECK name the programs themselves
#   CERTCYL_SHARDS   number of shards N (default 8); the array is 0..N-1
#   CERTCYL_TASKS    the array indices to submit (default 0-(N-1)); e.g. 3 or 3,5 re-runs only
#                    those shards once the first array has ended, and a new merge job waits
#                    for them
#   CERTCYL_CPUS     CPUs per task (--cpus-per-task, default 1): the tasks' threads
#   CERTCYL_OUT      results root (default: results); output in CERTCYL_OUT/CERTCYL_NAME, the
#                    jobs' logs in its slurm/ folder
#   CERTCYL_NAME     default: the study's size, or crosscheck-QUERY-CASES
#   CERTCYL_SEED     default 1
#   study:       CERTCYL_SIZE (default large), CERTCYL_STUDY_ARGS (more study options, e.g.
#                "--config FILE"), CERTCYL_PLOTS (1: the merge draws the figures when matplotlib
#                is there, the default; 0: it does not)
#   crosscheck:  CERTCYL_QUERY (line, triangle, cylinder or all; default cylinder), CERTCYL_CASES
#                (default 1000000), CERTCYL_FIRST (default 0)
# The study's merge job runs afterok: only when every task exited 0 (otherwise Slurm cancels it,
# and `certcyl merge` would refuse the missing shard anyway). The cross-check's runs afterany:
# a task that found a wrong answer exits 1, and the merge reports it with the counts, as it
# reports a shard that is missing. Prints the array job's and the merge job's ids on standard
# output, what was submitted on standard error.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
usage() {
  echo "usage: experiments/slurm/submit.sh study|crosscheck [sbatch options]" >&2
  exit 2
}
[ $# -ge 1 ] || usage
kind=$1
shift
command -v sbatch > /dev/null || { echo "submit: sbatch not found (not a Slurm submit host?)" >&2; exit 1; }

build=$(realpath -m "${CERTCYL_BUILD:-$repo/build}")
export CERTCYL_SHARDS=${CERTCYL_SHARDS:-8}
export CERTCYL_SEED=${CERTCYL_SEED:-1}
CERTCYL_OUT=$(realpath -m "${CERTCYL_OUT:-results}")
export CERTCYL_OUT
[[ "$CERTCYL_SHARDS" =~ ^[1-9][0-9]*$ ]] || { echo "submit: CERTCYL_SHARDS must be a positive integer, got '$CERTCYL_SHARDS'" >&2; exit 2; }
tasks=${CERTCYL_TASKS:-0-$((CERTCYL_SHARDS - 1))}
cpus=${CERTCYL_CPUS:-1}

case "$kind" in
  study)
    CERTCYL_BIN=$(realpath -m "${CERTCYL_BIN:-$build/bin/certcyl}")
    export CERTCYL_BIN
    export CERTCYL_SIZE=${CERTCYL_SIZE:-large}
    export CERTCYL_NAME=${CERTCYL_NAME:-$CERTCYL_SIZE}
    export CERTCYL_STUDY_ARGS=${CERTCYL_STUDY_ARGS:-}
    export CERTCYL_PLOTS=${CERTCYL_PLOTS:-1}
    program=$CERTCYL_BIN
    array_script=$here/study.sbatch
    merge=("$here/study-merge.sbatch")
    dependency=afterok
    ;;
  crosscheck)
    CERTCYL_CROSSCHECK=$(realpath -m "${CERTCYL_CROSSCHECK:-$build/experiments/crosscheck}")
    export CERTCYL_CROSSCHECK
    export CERTCYL_QUERY=${CERTCYL_QUERY:-cylinder}
    export CERTCYL_CASES=${CERTCYL_CASES:-1000000}
    export CERTCYL_FIRST=${CERTCYL_FIRST:-0}
    export CERTCYL_NAME=${CERTCYL_NAME:-crosscheck-$CERTCYL_QUERY-$CERTCYL_CASES}
    program=$CERTCYL_CROSSCHECK
    array_script=$here/crosscheck.sbatch
    merge=("$here/crosscheck-merge.sh" "$CERTCYL_OUT/$CERTCYL_NAME" "$CERTCYL_SHARDS")
    dependency=afterany
    ;;
  *) usage ;;
esac
[ -x "$program" ] || { echo "submit: $program not found: build it first (cmake --build $build --target certcyl_cli crosscheck)" >&2; exit 1; }

logs=$CERTCYL_OUT/$CERTCYL_NAME/slurm
mkdir -p "$logs"
array_id=$(sbatch --parsable --export=ALL --array="$tasks" --cpus-per-task="$cpus" \
  --output="$logs/%x-%A_%a.out" "$@" "$array_script")
array_id=${array_id%%;*}
merge_id=$(sbatch --parsable --export=ALL --dependency="$dependency:$array_id" --kill-on-invalid-dep=yes \
  --output="$logs/%x-%j.out" "$@" "${merge[@]}")
merge_id=${merge_id%%;*}
echo "submit: $kind, array job $array_id (tasks $tasks of $CERTCYL_SHARDS shards, $cpus CPU(s) each), merge job $merge_id ($dependency), into $CERTCYL_OUT/$CERTCYL_NAME" >&2
echo "$array_id $merge_id"
